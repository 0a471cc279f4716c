// expect: E2026 @11:7
function two
  input Real u;
  output Real a = u;
  output Real b = 2*u;
end two;
function f
  input Real u;
  output Real y;
algorithm
  (y, u) := two(u);
end f;
