// expect: E2027 @7:1
function f
  input Real u;
  output Real y;
algorithm
  y := u;
external "C";
end f;
