// Every attribute of the predefined types used where it exists.
type Mode = enumeration(A, B);
model M
  Real x(start = 1, fixed = true, nominal = 1, min = -10, max = 10, unit = "m",
    quantity = "Length", displayUnit = "mm", stateSelect = StateSelect.prefer);
  Integer n(start = 0, min = 0, max = 5, quantity = "Count");
  Boolean b(start = false);
  Mode m(start = Mode.A);
equation
  der(x) = -x;
  n = 1;
  b = time > 1;
  m = Mode.B;
end M;
