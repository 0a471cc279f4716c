// expect: E2025 @9:3
record R
  Real x;
end R;
model M
  parameter R r(x = 1);
  Real y;
algorithm
  r.x := 2;
  y := r.x;
end M;
