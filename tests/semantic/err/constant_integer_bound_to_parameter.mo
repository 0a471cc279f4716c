// expect: E2019 @4:24
model M
  parameter Integer n = 2;
  constant Integer m = n;
  Real x = m;
end M;
