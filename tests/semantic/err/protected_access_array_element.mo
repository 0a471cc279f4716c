// expect: E2022 @8:17
model A
protected
  Real v = 1;
end A;
model M
  A a[2];
  Real y = a[1].v;
end M;
