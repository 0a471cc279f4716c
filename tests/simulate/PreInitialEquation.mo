model PreInitialEquation "A hysteresis whose state before the start is set by `initial equation pre(y) = true` (the MSL's OnOffController): x rises from 0, turns at 1 and falls"
  discrete Boolean y;
  Real x(start = 0, fixed = true);
initial equation
  pre(y) = true;
equation
  y = pre(y) and x < 1 or x < -0.5;
  der(x) = if y then 1 else -1;
end PreInitialEquation;
