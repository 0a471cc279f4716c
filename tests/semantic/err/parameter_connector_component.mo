// expect: E2028 @8:17
// A connector component cannot be a parameter (spec 9.3).
connector Pin
  Real v;
  flow Real i;
end Pin;
model M
  parameter Pin p;
end M;
