model A
  Real x;
  Real y;
equation
  x + y;
  y = 1;
end A;
