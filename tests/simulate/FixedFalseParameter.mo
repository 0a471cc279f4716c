// A parameter computed by an initial equation (fixed = false): its start value (1) is
// only a guess. Taken at its start value, the two derivative rows would be singular
// (1 1; 1 1) and the analysis would expose a hidden constraint y = x that contradicts
// the fixed starts; with its value a = 2 the system is an ODE:
// der(x) = x - y, der(y) = y - 2 x.
model FixedFalseParameter
  parameter Real a(fixed = false, start = 1);
  Real x(start = 1, fixed = true);
  Real y(start = 0, fixed = true);
initial equation
  a = 2;
equation
  der(x) + der(y) = -x;
  a * der(x) + der(y) = -y;
end FixedFalseParameter;
