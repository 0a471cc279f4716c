// expect: E2024 @4:12
type Length = Real(unit = "m");
model M
  Length l(each start = 0);
equation
  l = 1;
end M;
