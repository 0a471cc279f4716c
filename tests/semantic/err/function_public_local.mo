// expect: E2028 @5:8
function f
  input Real u;
  output Real y;
  Real t;
algorithm
  t := 2*u;
  y := t;
end f;
