// A loop of three equations that tearing reduces to one iteration variable.
model AlgebraicLoop
  Real a, b, c;
  Real x(start = 1, fixed = true);
equation
  a = x + c;
  b = cos(a);
  c + sin(c) = b;
  der(x) = -c;
end AlgebraicLoop;
