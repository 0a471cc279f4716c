// A parameter with fixed = false is assigned in the initial algorithm (spec 8.6).
model M
  parameter Real p(fixed = false);
  Real x(start = 1, fixed = true);
initial algorithm
  p := 2;
equation
  der(x) = -p*x;
end M;
