// expect: E2033 @6:11
// A Real declared discrete must be assigned in a when clause.
model M
  discrete Real d;
equation
  d = 2 * time;
end M;
