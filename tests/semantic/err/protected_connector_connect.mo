// expect: E2022 @17:14
connector Pin
  Real v;
  flow Real i;
end Pin;
model A
  Pin p;
protected
  Pin q;
equation
  p.v = q.v;
  p.i + q.i = 0;
end A;
model M
  A a1, a2;
equation
  connect(a1.q, a2.p);
end M;
