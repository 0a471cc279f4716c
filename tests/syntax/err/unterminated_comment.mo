model A
  Real x;
  /* this comment never ends
equation
  x = 1;
end A;
