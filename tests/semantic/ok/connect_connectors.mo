// Connectors, arrays of connectors and connectors of components.
connector Pin
  Real v;
  flow Real i;
end Pin;
model R
  Pin p, n;
equation
  p.v - n.v = p.i;
  p.i + n.i = 0;
end R;
model G
  Pin p;
equation
  p.v = 0;
end G;
model M
  R r[2];
  G g;
equation
  connect(r[1].n, r[2].p);
  connect(r[2].n, g.p);
  connect(r[1].p, g.p);
end M;
