// expect: E2024 @10:7
model A
  parameter Real k = 1;
  Real y = k;
end A;
model B
  A a;
end B;
model M
  B b(each a.k = 2);
end M;
