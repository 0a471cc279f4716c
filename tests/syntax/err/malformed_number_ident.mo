model A
  Real 2x;
equation
end A;
