// expect: E2004 @3:22
model M
  parameter String s(unit = "m") = "a";
end M;
