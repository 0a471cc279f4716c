// expect: E2004 @3:16
model M
  Real x(foo = 1) = 1;
end M;
