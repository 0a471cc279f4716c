// expect: E2023 @13:7
model Base
  Real y;
protected
  parameter Real k = 1;
equation
  y = k;
end Base;
model A
  extends Base;
end A;
model M
  A a(k = 3);
end M;
