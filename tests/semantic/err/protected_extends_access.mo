// expect: E2022 @11:14
model Base
  Real x = 1;
end Base;
model A
protected
  extends Base;
end A;
model M
  A a;
  Real y = a.x;
end M;
