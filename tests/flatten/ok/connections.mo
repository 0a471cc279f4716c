connector Pin
  Real v;
  flow Real i;
end Pin;

model TwoPin
  Pin p, n;
  Real v, i;
equation
  v = p.v - n.v;
  0 = p.i + n.i;
  i = p.i;
end TwoPin;

model Resistor
  extends TwoPin;
  parameter Real R = 1;
equation
  v = R * i;
end Resistor;

model Capacitor
  extends TwoPin;
  parameter Real C = 1;
equation
  i = C * der(v);
end Capacitor;

model Ground
  Pin p;
equation
  p.v = 0;
end Ground;

model Connections "an RC loop: potentials equal, flows sum to zero"
  Resistor r(R = 10);
  Capacitor c(C = 0.01, v(start = 1, fixed = true));
  Ground g;
equation
  connect(r.p, c.p);
  connect(r.n, c.n);
  connect(c.n, g.p);
end Connections;
