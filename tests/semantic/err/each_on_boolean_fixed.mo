// expect: E2024 @3:13
model M
  Boolean b(each fixed = false, start = false);
equation
  b = time > 1;
end M;
