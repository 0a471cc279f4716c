// expect: E2027 @5:1
function f
  input Real u;
  output Real y;
initial algorithm
  y := u;
end f;
