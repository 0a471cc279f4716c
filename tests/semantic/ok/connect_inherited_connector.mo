// A connector inherited from a base class.
connector Pin
  Real v;
  flow Real i;
end Pin;
model OnePort
  Pin p;
end OnePort;
model A
  extends OnePort;
equation
  p.i = p.v - 1;
end A;
model M
  A a1, a2;
equation
  connect(a1.p, a2.p);
end M;
