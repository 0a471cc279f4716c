model ClockedNotSupported "A clocked built-in: parsed and named, then reported as not supported"
  Real x(start = 0, fixed = true);
  Real y;
equation
  der(x) = 1;
  y = previous(x);
end ClockedNotSupported;
