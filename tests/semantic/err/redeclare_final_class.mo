// expect: E2016 @14:23
// A final replaceable class cannot be redeclared either.
model A
  Real y = 1;
end A;
model B
  extends A;
end B;
model P
  final replaceable model X = A;
  X x;
end P;
model M
  P p(redeclare model X = B);
end M;
