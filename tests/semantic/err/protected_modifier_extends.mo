// expect: E2023 @11:7
model Base
  parameter Real k = 1;
  Real y = k;
end Base;
model A
protected
  extends Base;
end A;
model M
  A a(k = 2);
end M;
