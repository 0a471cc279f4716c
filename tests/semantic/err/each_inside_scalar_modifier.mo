// expect: E2024 @3:20
model M
  parameter Real p(each nominal = 2) = 1;
  Real x(start = p, fixed = true);
equation
  der(x) = -x;
end M;
