// Parameters inside a connector are fine; only connector components may not be parameters.
connector Pin
  Real v;
  flow Real i;
end Pin;
connector Plug
  parameter Integer m = 2;
  Pin pin[m];
end Plug;
record Data
  Real r = 1;
end Data;
model Resistors
  parameter Data data;
  Plug plug;
equation
  for k in 1:2 loop
    plug.pin[k].v = data.r * plug.pin[k].i;
  end for;
end Resistors;
