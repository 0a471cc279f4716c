model FixedFalseStructural "A parameter computed by initial equations (fixed = false) has no value at translation: its start value is only a guess"
  parameter Integer n(fixed = false, start = 2);
  Real x[n];
initial equation
  n = 3;
equation
  x = fill(time, 2);
end FixedFalseStructural;
