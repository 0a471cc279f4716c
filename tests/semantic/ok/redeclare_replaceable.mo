// A redeclaration of a replaceable component.
model A
  Real y = 1;
end A;
model B
  extends A;
end B;
model P
  replaceable A a;
end P;
model M
  P p(redeclare B a);
end M;
