// Two different elements of one connector array.
connector Pin
  Real v;
  flow Real i;
end Pin;
model Node
  Pin p[2];
equation
  connect(p[1], p[2]);
end Node;
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
  Node node;
  R r1, r2;
  G g;
equation
  connect(r1.p, node.p[1]);
  connect(r2.p, node.p[2]);
  connect(r1.n, g.p);
  connect(r2.n, g.p);
end M;
