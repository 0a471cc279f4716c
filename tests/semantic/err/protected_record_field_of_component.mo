// expect: E2022 @11:14
record R
  Real x;
end R;
model A
protected
  R r(x = 1);
end A;
model M
  A a;
  Real y = a.r.x;
end M;
