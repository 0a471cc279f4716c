// A function assigns its outputs and protected locals, reads its inputs.
function f
  input Real u;
  input Real w[2];
  output Real y;
protected
  Real t;
  constant Real c = 2;
algorithm
  t := c*u + sum(w);
  y := t;
end f;
model M
  Real x = f(1, {2, 3});
end M;
