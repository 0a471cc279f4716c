// expect: E2008 @3:22
model M
  parameter Real a = c + 1;
  parameter Real b = a;
  parameter Real c = b;
  Real x = a;
end M;
