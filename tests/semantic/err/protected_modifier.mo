// expect: E2023 @10:7
model A
  Real y;
protected
  parameter Real k = 1;
equation
  y = k;
end A;
model M
  A a(k = 2);
end M;
