// Arrays count by scalars; inputs, parameters and constants are not potentials.
connector Plug
  parameter Integer m = 2;
  Real v[2];
  flow Real i1;
  flow Real i2;
  input Real u;
end Plug;
model M
  Plug p;
equation
  p.v[1] = 1;
  p.v[2] = 2;
end M;
