// expect: E2021 @3:8
model M
  flow Boolean b = true;
end M;
