// expect: E2020 @6:12
model M
  Integer n = integer(time);
  Boolean b;
equation
  b = edge(n);
end M;
