model FreeParameter "a parameter with fixed = false solved by an initial equation"
  parameter Real k(fixed = false, start = 1);
  parameter Real k2 = 2 * k "depends on the free parameter";
  Real y = k2;
  Real x(start = 2, fixed = true);
initial equation
  k * k = 9;
equation
  der(x) = -k * x;
end FreeParameter;
