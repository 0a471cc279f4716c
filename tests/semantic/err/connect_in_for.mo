// expect: E2030 @9:13, E2030 @9:19
model A
  Real v = 1;
end A;
model M
  A a[3];
equation
  for i in 1:2 loop
    connect(a[i], a[i + 1]);
  end for;
end M;
