// expect: E2022 @11:14
model Base
protected
  Real x = 1;
end Base;
model A
  extends Base;
end A;
model M
  A a;
  Real y = a.x;
end M;
