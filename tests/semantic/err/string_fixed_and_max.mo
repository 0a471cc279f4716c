// expect: E2004 @3:36
model M
  parameter String s(fixed = true, max = "z") = "a";
end M;
