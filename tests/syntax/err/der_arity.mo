model A
  Real x;
equation
  der(x, 2) = 1;
end A;
