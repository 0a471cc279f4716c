model A
  Real x;
  Real y;
equation
  x = (y, 1);
  y = 2;
end A;
