// expect: E2025 @6:3
model M
  constant Real c = 1;
  Real x(start = 0, fixed = false);
initial algorithm
  c := 2;
equation
  der(x) = -x;
end M;
