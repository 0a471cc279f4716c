// expect: E2027 @6:5
block B
  output Real y = 1;
end B;
record R
  B b;
end R;
