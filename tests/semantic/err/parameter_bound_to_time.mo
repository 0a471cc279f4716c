// expect: E2019 @3:22
model M
  parameter Real p = time;
  Real x = p;
end M;
