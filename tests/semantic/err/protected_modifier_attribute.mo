// expect: E2023 @9:7
model A
protected
  Real x(start = 0, fixed = true);
equation
  der(x) = 1;
end A;
model M
  A a(x(start = 1));
end M;
