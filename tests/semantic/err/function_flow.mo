// expect: E2028 @6:13
function f
  input Real u;
  output Real y;
protected
  flow Real i;
algorithm
  y := u;
end f;
