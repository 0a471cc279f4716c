// expect: E2030 @13:14
model Base
  Real x = 1;
end Base;
model A
  extends Base;
end A;
connector C = input Real;
model M
  A a;
  C c;
equation
  connect(c, a.x);
end M;
