// expect: E2006 @12:3
connector A
  Real s;
end A;
connector B
  Boolean s;
end B;
model M
  A a;
  B b;
equation
  connect(a, b);
end M;
