// expect: E2030 @10:11, E2030 @10:16
connector C
  parameter Real k = 1;
  Real v;
  flow Real i;
end C;
model M
  C a, b;
equation
  connect(a.k, b.k);
end M;
