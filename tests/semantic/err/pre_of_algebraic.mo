// expect: E2032 @6:11
model M
  Real x = time;
  Boolean b;
equation
  b = pre(x) > 1;
end M;
