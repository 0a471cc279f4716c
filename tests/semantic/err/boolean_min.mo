// expect: E2004 @3:13
model M
  Boolean b(min = false) = time > 1;
end M;
