// expect: E2025 @6:3
model M
  parameter Real p[2] = {1, 2};
  Real x;
algorithm
  p[1] := 0;
  x := 1;
end M;
