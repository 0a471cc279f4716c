// expect: E2024 @7:7
record R
  Real x;
  Real z;
end R;
model M
  R r(each x = 1, z = 2);
end M;
