// A constant reading the size of a parameter array (structure, not value).
model M
  parameter Real p[3] = {1, 2, 3};
  constant Integer n = 3;
  parameter Integer m = size(p, 1);
  Real x = n + m;
end M;
