// An input with a default value is still only read.
function f
  input Real u;
  input Real k = 2;
  output Real y;
algorithm
  y := k*u;
end f;
model M
  Real x = f(1);
end M;
