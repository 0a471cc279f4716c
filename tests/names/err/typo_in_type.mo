model A
  Rael x;
equation
  x = 1;
end A;
