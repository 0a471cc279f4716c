// expect: E2030 @10:14
connector Pin
  Real v;
  flow Real i;
end Pin;
model M
  Pin p;
  Real x;
equation
  connect(p, x);
end M;
