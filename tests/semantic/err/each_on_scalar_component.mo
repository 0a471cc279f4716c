// expect: E2024 @7:7
model A
  parameter Real k = 1;
  Real y = k;
end A;
model M
  A a(each k = 2);
end M;
