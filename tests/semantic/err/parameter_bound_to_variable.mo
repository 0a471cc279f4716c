// expect: E2019 @4:22
model M
  Real x = time;
  parameter Real p = 2*x;
end M;
