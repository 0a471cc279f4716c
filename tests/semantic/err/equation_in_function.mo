// expect: E1221 @5:1
function f
  input Real u;
  output Real y;
equation
  y = u;
end f;
