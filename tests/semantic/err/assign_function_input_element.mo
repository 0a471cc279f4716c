// expect: E2026 @6:3
function f
  input Real u[2];
  output Real y;
algorithm
  u[1] := 0;
  y := sum(u);
end f;
