// expect: E2033 @9:18
// An enumeration variable given a value that depends on a derivative.
type Mode = enumeration(off, on);
model M
  Real x(start = 0, fixed = true);
  Mode m;
equation
  der(x) = 1;
  m = if noEvent(der(x) > 0) then Mode.on else Mode.off;
end M;
