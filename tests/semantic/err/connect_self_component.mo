// expect: E2031 @15:3
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
model M
  R r;
equation
  connect(r.p, r.p);
end M;
