// expect: E2019 @4:24
model M
  parameter Real p[2] = {1, 2};
  constant Real c[2] = p;
  Real x[2] = c;
end M;
