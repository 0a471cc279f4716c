// expect: E2006 @9:3
connector Pin
  Real v;
  flow Real i;
end Pin;
model M
  Pin a[2], b[3];
equation
  connect(a, b);
end M;
