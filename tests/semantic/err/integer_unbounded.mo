// expect: E2004 @3:13
model M
  Integer n(unbounded = true) = 1;
end M;
