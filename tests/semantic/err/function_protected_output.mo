// expect: E2028 @6:15
function f
  input Real u;
  output Real y;
protected
  output Real z;
algorithm
  y := u;
end f;
