// expect: E2020 @6:11
model M
  Integer n = integer(time);
  Real y;
equation
  y = der(n);
end M;
