// expect: E2033 @8:12
// Integer array elements given continuous values in a for equation.
model M
  Real x[2] = {time, 2 * time};
  Integer i[2];
equation
  for k in 1:2 loop
    i[k] = x[k];
  end for;
end M;
