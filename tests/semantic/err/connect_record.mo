// expect: E2030 @8:11, E2030 @8:15
record R
  Real x;
end R;
model M
  R r1, r2;
equation
  connect(r1, r2);
end M;
