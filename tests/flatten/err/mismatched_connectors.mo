connector A
  Real v;
  flow Real i;
end A;

connector B
  Real v;
  Real w;
end B;

model MismatchedConnectors
  A a;
  B b;
equation
  connect(a, b);
end MismatchedConnectors;
