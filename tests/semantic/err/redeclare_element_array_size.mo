// expect: E2015 @8:18
// A redeclare element of a class obeys the same rule as a modifier.
model P
  replaceable Real x[3] = {1, 2, 3};
end P;
model M
  extends P;
  redeclare Real x[4];
end M;
