// expect: E2022 @10:10
model A
protected
  Real v = time;
end A;
model M
  A a;
  Real y;
algorithm
  y := a.v;
end M;
