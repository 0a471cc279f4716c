// expect: E2030 @13:14
connector Pin
  Real v;
  flow Real i;
end Pin;
model A
  Real x = 1;
end A;
model M
  Pin p;
  A a;
equation
  connect(p, a.x);
end M;
