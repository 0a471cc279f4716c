model A
  Real x(start = 1);
equation
  der(x) = -1;
  reinit(x, 0);
end A;
