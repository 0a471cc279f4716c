// expect: E2028 @6:14
function f
  input Real u;
  output Real y;
protected
  input Real w;
algorithm
  y := u;
end f;
