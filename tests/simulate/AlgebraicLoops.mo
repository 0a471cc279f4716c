// Nonlinear algebraic loops with closed-form solutions: each is a Newton block (no
// variable of them can be solved for symbolically), so how exactly the blocks are
// solved shows in the result, not the integrator's error.
model AlgebraicLoops
  Real s(start = 0, fixed = true) "a state, so the solver steps";
  Real y(start = 0) "y^3 + y = t^3 + t: y = t";
  Real a(start = 1) "a + b^3 = cos(t) + sin(t)^3, a^3 - b = cos(t)^3 - sin(t): a = cos(t)";
  Real b(start = 0) "b = sin(t) (the loop's Jacobian has determinant -1 - 9 a^2 b^2)";
  Real z(start = 0) "a residual scaled by 1e-12: z = t";
equation
  der(s) = 1;
  y ^ 3 + y = time ^ 3 + time;
  a + b ^ 3 = cos(time) + sin(time) ^ 3;
  a ^ 3 - b = cos(time) ^ 3 - sin(time);
  1e-12 * (exp(z) + z) = 1e-12 * (exp(time) + time);
end AlgebraicLoops;
