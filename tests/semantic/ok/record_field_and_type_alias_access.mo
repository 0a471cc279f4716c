// Fields of records are elements; a Real type alias with a unit is still read whole.
type Voltage = Real(unit = "V");
record Data
  Voltage v0 = 1;
end Data;
model M
  parameter Data data;
  Voltage v = data.v0;
end M;
