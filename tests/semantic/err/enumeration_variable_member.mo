// expect: E2001 @6:17
// A variable of an enumeration type has no elements either.
type Mode = enumeration(off, on);
model M
  Mode m = Mode.on;
  Boolean b = m.on;
end M;
