// A record with parameters, constants and a nested record.
record Inner
  Real a;
end Inner;
record R
  parameter Real k = 1;
  constant Integer n = 2;
  Inner i;
  Real x[2];
end R;
model M
  R r(i(a = 1), x = {1, 2});
end M;
