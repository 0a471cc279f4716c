// expect: E2004 @4:20
type Mode = enumeration(A, B);
model M
  parameter Mode m(unit = "1") = Mode.A;
end M;
