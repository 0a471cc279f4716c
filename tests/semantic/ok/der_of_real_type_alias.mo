// `der` of a variable whose type derives from Real.
type Position = Real(unit = "m");
model M
  Position s(start = 0, fixed = true);
equation
  der(s) = 1;
end M;
