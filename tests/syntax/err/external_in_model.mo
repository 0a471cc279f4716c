model M
  Real x;
equation
  x = 1;
external "C";
end M;
