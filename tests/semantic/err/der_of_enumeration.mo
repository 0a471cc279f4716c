// expect: E2020 @7:11
type Mode = enumeration(A, B);
model M
  Mode m = if time > 1 then Mode.B else Mode.A;
  Real y;
equation
  y = der(m);
end M;
