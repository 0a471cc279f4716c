// expect: E2026 @9:3
record R
  Real x;
end R;
function f
  input R r;
  output Real y;
algorithm
  r.x := 1;
  y := r.x;
end f;
