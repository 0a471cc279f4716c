// expect: E2008 @3:22
model M
  parameter Real a = 2*a;
  Real x = a;
end M;
