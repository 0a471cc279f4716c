// `array(a, b, c)` is the array constructor `{a, b, c}` (spec 10.4), as the MSL's
// water property functions write their coefficient tables.
model ArrayConstructor
  constant Real n[3] = array(1.5, 2.5, 3.5);
  parameter Integer k = size(array(1, 2), 1);
  Real y[3];
equation
  y = array(time, 2 * time, n[3] * time);
end ArrayConstructor;
