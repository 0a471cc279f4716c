// expect: E2027 @9:1
function f
  input Real u;
  output Real y;
protected
  Real t;
algorithm
  t := u;
algorithm
  y := t;
end f;
