// expect: E2006 @14:3
connector A
  Real v;
  flow Real i;
end A;
connector B
  Real v;
  Real i;
end B;
model M
  A a;
  B b;
equation
  connect(a, b);
end M;
