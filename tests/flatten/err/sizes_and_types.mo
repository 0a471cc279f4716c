model SizesAndTypes
  Real x[3];
  Real y;
  Boolean b;
  Integer i;
equation
  x[1, 2] = 1;
  x[2] = 2;
  x[3] = 3;
  y = x;
  b = 1.5;
  i = 2;
end SizesAndTypes;
