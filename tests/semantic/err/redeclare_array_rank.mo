// expect: E2015 @7:22
// A redeclared component keeps its number of dimensions.
model P
  replaceable Real x[3] = {1, 2, 3};
end P;
model M
  P p(redeclare Real x[3, 3]);
end M;
