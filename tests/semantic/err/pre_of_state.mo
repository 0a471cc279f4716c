// expect: E2032 @7:11
model M
  Real x(start = 1, fixed = true);
  Real y;
equation
  der(x) = -x;
  y = pre(x);
end M;
