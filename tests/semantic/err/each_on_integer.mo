// expect: E2024 @3:13
model M
  Integer n(each start = 0);
equation
  n = 1;
end M;
