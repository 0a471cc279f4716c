// A flow variable of type Real, of a Real type alias and a Real array.
type Current = Real(unit = "A");
connector Pin
  Real v;
  flow Current i;
  flow Real j[2];
end Pin;
