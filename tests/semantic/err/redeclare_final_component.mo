// expect: E2016 @13:19
// A final element cannot be redeclared.
model A
  Real y = 1;
end A;
model B
  extends A;
end B;
model P
  final replaceable A a;
end P;
model M
  P p(redeclare B a);
end M;
