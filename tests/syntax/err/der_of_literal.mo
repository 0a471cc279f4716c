model A
  Real x;
equation
  x = der(3.0);
end A;
