// expect: E2024 @3:10
model M
  Real x(each start = 1);
equation
  x = 1;
end M;
