// expect: E2022 @8:12
model A
protected
  parameter Integer n = 2;
end A;
model M
  A a;
  Real x[a.n] = {1, 2};
end M;
