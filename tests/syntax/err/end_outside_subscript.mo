model A
  Real x;
equation
  x = end;
end A;
