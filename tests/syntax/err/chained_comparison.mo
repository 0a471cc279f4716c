model A
  Real x = 1;
  Boolean b;
equation
  b = 0 < x < 2;
end A;
