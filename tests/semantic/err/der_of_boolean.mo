// expect: E2020 @6:11
model M
  Boolean b = time > 1;
  Real y;
equation
  y = der(b);
end M;
