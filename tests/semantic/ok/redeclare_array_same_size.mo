// A redeclaration with the same dimensions, and one sized by a parameter.
model P
  parameter Integer n = 3;
  replaceable Real x[3] = {1, 2, 3};
  replaceable Real z[3] = {1, 2, 3};
end P;
model M
  P p(redeclare Real x[3], redeclare Real z[p.n]);
end M;
