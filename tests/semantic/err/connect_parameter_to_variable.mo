// expect: E2006 @18:3
// A parameter of one connector matched with a variable of the other.
connector A
  parameter Real k = 1;
  Real p;
  flow Real f;
end A;
connector B
  Real k;
  Real p;
  flow Real f;
  flow Real g;
end B;
model M
  A a;
  B b;
equation
  connect(a, b);
end M;
