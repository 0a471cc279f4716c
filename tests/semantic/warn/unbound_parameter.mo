model UnboundParameter "A parameter without a value warns (W2001); one computed by initial equations or with a start value does not"
  parameter Real k;
  parameter Real a(fixed = false);
  parameter Real c(start = 2);
  parameter Integer n;
  Real x(start = 1, fixed = true);
initial equation
  a = 1;
equation
  der(x) = -k * x + a + c + n;
end UnboundParameter;
