// expect: E2019 @8:11
model A
  constant Real c = 1;
  Real y = c;
end A;
model M
  parameter Real p = 2;
  A a(c = p);
end M;
