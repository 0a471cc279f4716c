model A
  Real x;
equation
  x = f[1](2);
end A;
