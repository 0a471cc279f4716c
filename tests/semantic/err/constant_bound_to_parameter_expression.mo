// expect: E2019 @4:21
model M
  parameter Real p = 1;
  constant Real c = 2*p + 1;
  Real x = c;
end M;
