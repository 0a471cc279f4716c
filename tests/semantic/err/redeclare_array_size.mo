// expect: E2015 @7:22
// A redeclared array component keeps its size.
model P
  replaceable Real x[3] = {1, 2, 3};
end P;
model M
  P p(redeclare Real x[2]);
end M;
