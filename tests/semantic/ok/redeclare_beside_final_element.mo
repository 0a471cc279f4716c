// A final element beside a replaceable one: redeclaring the replaceable one is fine.
model A
  Real y = 1;
end A;
model B
  extends A;
end B;
model P
  final A fixed;
  replaceable A a;
end P;
model M
  P p(redeclare B a);
end M;
