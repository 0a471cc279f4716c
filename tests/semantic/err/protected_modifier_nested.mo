// expect: E2023 @13:9
model A
  Real y;
protected
  parameter Real k = 1;
equation
  y = k;
end A;
model B
  A a;
end B;
model M
  B b(a(k = 2));
end M;
