// expect: E2022 @11:9
model A
  Real y = 1;
protected
  Real v = 2;
end A;
model M
  A a;
  Real z;
equation
  z = a.v;
end M;
