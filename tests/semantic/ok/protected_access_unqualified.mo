// A class reads its own protected elements without dot notation.
model M
  Real y;
protected
  parameter Real k = 2;
  Real z = k;
equation
  y = z;
end M;
