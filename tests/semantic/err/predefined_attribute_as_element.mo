// expect: E2001 @8:9
// The start attribute of a Real is not an element: x.start denotes nothing.
model M
  Real x(start = 1, fixed = true);
  Real y;
equation
  der(x) = -x;
  y = x.start;
end M;
