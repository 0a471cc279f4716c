model A
  Real x;
equation
  x = (1 + 2;
end A;
