// expect: E2008 @3:21
model M
  constant Real a = b;
  constant Real b = a;
  Real x = a;
end M;
