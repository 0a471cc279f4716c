// expect: E2006 @17:3
// Constants connect to constants only.
connector A
  constant Integer n = 2;
  Real p;
  flow Real f;
end A;
connector B
  parameter Integer n = 2;
  Real p;
  flow Real f;
end B;
model M
  A a;
  B b;
equation
  connect(a, b);
end M;
