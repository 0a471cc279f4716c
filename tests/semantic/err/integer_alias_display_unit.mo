// expect: E2004 @4:21
type Count = Integer;
model M
  parameter Count c(displayUnit = "1") = 1;
end M;
