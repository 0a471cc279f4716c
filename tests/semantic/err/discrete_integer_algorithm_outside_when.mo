// expect: E2033 @7:8
// An assignment outside when: the Integer would take a continuous value.
model M
  Real x = time;
  Integer i;
algorithm
  i := x;
end M;
