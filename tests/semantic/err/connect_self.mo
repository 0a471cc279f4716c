// expect: E2031 @9:3
connector Pin
  Real v;
  flow Real i;
end Pin;
model M
  Pin p;
equation
  connect(p, p);
end M;
