// expect: E2033 @5:15
// The binding of an Integer variable is an equation like any other.
model M
  Real x = time;
  Integer n = x;
end M;
