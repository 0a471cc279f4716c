// expect: E2022 @11:13
model A
protected
  parameter Real k = 1;
end A;
model B
  parameter Real g = 1;
end B;
model M
  A a;
  B b(g = a.k);
end M;
