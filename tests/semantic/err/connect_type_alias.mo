// expect: E2030 @6:11, E2030 @6:15
type Voltage = Real(unit = "V");
model M
  Voltage v1, v2;
equation
  connect(v1, v2);
end M;
