// expect: E2004 @3:13
model M
  Integer n(unit = "1") = 1;
end M;
