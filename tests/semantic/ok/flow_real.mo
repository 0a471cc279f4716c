// A flow variable of type Real, of a Real type alias and a Real array (as many
// potential variables as flow ones, spec 9.3.1).
type Current = Real(unit = "A");
connector Pin
  Real v;
  Real u[2];
  flow Current i;
  flow Real j[2];
end Pin;
