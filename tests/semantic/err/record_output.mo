// expect: E2028 @3:15
record R
  output Real y;
end R;
