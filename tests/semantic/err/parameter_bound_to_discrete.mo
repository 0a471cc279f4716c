// expect: E2019 @4:25
model M
  Integer n = integer(time);
  parameter Integer m = n;
  Real x = m;
end M;
