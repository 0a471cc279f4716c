// expect: E2030 @8:11, E2030 @8:14
model A
  Real v = 1;
end A;
model M
  A a, b;
equation
  connect(a, b);
end M;
