// expect: E2022 @10:16
model A
protected
  parameter Integer n = 2;
end A;
model M
  A a;
  Real x[2];
equation
  for i in 1:a.n loop
    x[i] = i;
  end for;
end M;
