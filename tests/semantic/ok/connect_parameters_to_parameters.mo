// Parameters of connected connectors: matched with parameters (an assert, no equation).
connector A
  parameter Real k = 1;
  Real p;
  flow Real f;
end A;
model S
  A a;
equation
  a.p = 1;
end S;
model L
  A a;
equation
  a.f = 1;
end L;
model M
  S s;
  L l;
equation
  connect(s.a, l.a);
end M;
