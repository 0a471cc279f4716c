// A function that extends a partial function assigns the inherited output.
partial function Base
  input Real u;
  output Real y;
end Base;
function f
  extends Base;
algorithm
  y := 2*u;
end f;
model M
  Real x = f(1);
end M;
