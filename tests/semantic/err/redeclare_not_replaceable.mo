// expect: E2015 @12:17
model A
  Real y = 1;
end A;
model B
  Real y = 2;
end B;
model P
  A a;
end P;
model M
  P p(redeclare B a);
end M;
