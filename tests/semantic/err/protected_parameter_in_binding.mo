// expect: E2022 @8:24
model A
protected
  parameter Real k = 1;
end A;
model M
  A a;
  parameter Real p = a.k;
end M;
