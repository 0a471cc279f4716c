// expect: E2032 @9:13
model A
  Real v = time;
end A;
model M
  A a;
  Real y;
equation
  y = 2*pre(a.v);
end M;
