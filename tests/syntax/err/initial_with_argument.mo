model A
  Real x;
equation
  x = if initial(1) then 1 else 2;
end A;
