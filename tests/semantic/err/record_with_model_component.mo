// expect: E2027 @7:5
model A
  Real y = 1;
end A;
record R
  Real x;
  A a;
end R;
