model A
  Real x;
equation
  x = 1.5e+;
end A;
