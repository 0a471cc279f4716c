// expect: E2025 @9:3
model Base
  parameter Real k = 1;
end Base;
model M
  extends Base;
  Real x;
algorithm
  k := 2;
  x := k;
end M;
