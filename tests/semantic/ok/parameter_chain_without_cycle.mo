// Parameters bound to each other without a cycle.
model M
  parameter Real a = 1;
  parameter Real b = a + 1;
  parameter Real c = a + b;
  Real x = c;
end M;
