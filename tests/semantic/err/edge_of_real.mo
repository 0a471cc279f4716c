// expect: E2020 @6:12
model M
  Real x = time;
  Boolean b;
equation
  b = edge(x);
end M;
