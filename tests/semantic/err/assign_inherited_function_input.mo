// expect: E2026 @9:3
partial function Base
  input Real u;
  output Real y;
end Base;
function f
  extends Base;
algorithm
  u := 1;
  y := u;
end f;
