// expect: E2025 @6:3
model M
  constant Real c = 1;
  Real x;
algorithm
  c := 2;
  x := c;
end M;
