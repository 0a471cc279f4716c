// expect: E2024 @3:20
model M
  parameter Real p(each min = 0) = 1;
  Real y = p;
end M;
