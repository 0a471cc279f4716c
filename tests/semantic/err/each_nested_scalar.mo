// expect: E2024 @10:9
model A
  parameter Real k = 1;
  Real y = k;
end A;
model B
  A a;
end B;
model M
  B b(a(each k = 2));
end M;
