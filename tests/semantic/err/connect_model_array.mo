// expect: E2030 @8:11, E2030 @8:17
model A
  Real v = 1;
end A;
model M
  A a[2];
equation
  connect(a[1], a[2]);
end M;
