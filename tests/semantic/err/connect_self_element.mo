// expect: E2031 @9:3
connector Pin
  Real v;
  flow Real i;
end Pin;
model M
  Pin p[2];
equation
  connect(p[1], p[1]);
end M;
