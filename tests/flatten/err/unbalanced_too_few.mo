model UnbalancedTooFew
  Real x(start = 1, fixed = true);
  Real y;
  Real z;
equation
  der(x) = -x;
  y = 2 * x;
end UnbalancedTooFew;
