model A
  Real x = 1;
equation
  assert(x > 0);
end A;
