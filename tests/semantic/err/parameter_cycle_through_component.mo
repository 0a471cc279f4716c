// expect: E2008 @7:22
model A
  parameter Real k = 1;
end A;
model M
  A a(k = p);
  parameter Real p = a.k;
  Real x = p;
end M;
