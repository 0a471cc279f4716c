// expect: E2025 @11:4
function two
  input Real u;
  output Real a = u;
  output Real b = 2*u;
end two;
model M
  parameter Real p = 1;
  Real x;
algorithm
  (p, x) := two(1);
end M;
