// expect: E2025 @8:3
function f
  input Real u;
  output Real y;
protected
  constant Real c = 2;
algorithm
  c := 3;
  y := c*u;
end f;
