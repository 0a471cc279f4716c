model ConstantFolding
  "a component constant decides an if-branch, as MSL's KinematicPTP2 `eps`: both y and
   z fold to constants (removed as such), so the DAE keeps only x"
  constant Real eps = 10 * 2.2e-16;
  parameter Real p = 2;
  Real y;
  Real z;
  Real x(start = 0, fixed = true);
equation
  y = if p <= eps then 0 else 1 / p;
  z = if y > eps then 2 * y else 0;
  der(x) = z;
end ConstantFolding;
