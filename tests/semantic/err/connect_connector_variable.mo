// expect: E2030 @9:11, E2030 @9:16
connector Pin
  Real v;
  flow Real i;
end Pin;
model M
  Pin a, b;
equation
  connect(a.v, b.v);
end M;
