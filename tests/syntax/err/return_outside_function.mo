model A
  Real x;
algorithm
  x := 1;
  return;
end A;
