// expect: E2028 @5:8
function f
  input Real u[2];
  output Real y;
  Real t[2];
algorithm
  t := 2*u;
  y := sum(t);
end f;
