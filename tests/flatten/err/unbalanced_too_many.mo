model UnbalancedTooMany
  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
  x = 2;
end UnbalancedTooMany;
