// expect: E1221 @4:1
record R
  Real x;
equation
  x = 1;
end R;
