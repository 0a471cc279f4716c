// A nonlinear algebraic loop (y + log(y) = x cannot be solved for y symbolically):
// Newton's method solves it at every evaluation, starting from the last solution.
model Restart
  Real x(start = 1, fixed = true);
  Real y(start = 1);
equation
  der(x) = -y;
  y + log(y) = x;
end Restart;
