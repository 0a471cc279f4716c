// A function assigns a field of its record output.
record R
  Real x;
  Real y;
end R;
function f
  input Real u;
  output R r;
algorithm
  r.x := u;
  r.y := 2*u;
end f;
model M
  R r = f(1);
end M;
