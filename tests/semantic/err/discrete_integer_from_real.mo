// expect: E2033 @7:7
// An Integer variable equated to a continuous-time Real outside a when clause.
model M
  Real x = time;
  Integer i;
equation
  i = x;
end M;
