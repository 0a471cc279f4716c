model A
  Real x
end A;

model B
  Real y;
equation
  y = 1 +;
end B;
