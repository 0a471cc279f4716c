// expect: E2023 @10:15
model A
  Real y;
protected
  parameter Real k = 1;
equation
  y = k;
end A;
model M
  A a[2](each k = 2);
end M;
