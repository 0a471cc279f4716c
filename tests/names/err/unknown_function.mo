model A
  Real x;
equation
  x = sinn(time);
end A;
