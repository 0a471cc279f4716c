// expect: E2033 @7:20
// integer(x) is discrete-time, but adding x back makes the sum continuous.
model M
  Real x = time;
  Integer i;
equation
  i = integer(x) + x;
end M;
