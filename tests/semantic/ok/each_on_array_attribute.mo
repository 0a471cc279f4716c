// `each` on an attribute of an array variable.
model M
  Real x[3](each start = 0, each fixed = true);
equation
  der(x) = {1, 2, 3};
end M;
