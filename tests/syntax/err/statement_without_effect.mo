model A
  Real x;
algorithm
  x;
end A;
