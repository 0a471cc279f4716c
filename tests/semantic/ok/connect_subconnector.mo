// A connector inside a connector (a sub-connector) is a connector.
connector Pin
  Real v;
  flow Real i;
end Pin;
connector Plug
  Pin a;
  Pin b;
end Plug;
model M
  Plug p1, p2;
equation
  connect(p1.a, p2.b);
  connect(p1.b, p2.a);
  p1.a.v = 1;
  p1.a.i = 1;
  p1.b.v = 2;
  p1.b.i = 2;
end M;
