// Enumeration literals through the type's name.
type Mode = enumeration(Off, On);
model M
  parameter Mode m = Mode.On;
  Real y = if m == Mode.On then 1 else 0;
end M;
