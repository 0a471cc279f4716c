model A
  Real x = 1e999;
end A;
