// expect: E2037 @3:11
// A connector with flow variables needs as many flow as potential variables.
connector Pin
  Real v;
  Real w;
  flow Real i;
end Pin;
model M
  Pin p;
end M;
