// expect: E2016 @13:25
// The rule holds for redeclarations in an extends modifier.
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
  extends P(redeclare B a);
end M;
