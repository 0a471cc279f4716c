// `size(x, k)` of a variable that is not a parameter is known from its declaration:
// a `for` range over it unrolls at compile time (the MSL's LossyGear).
model SizeOfVariables
  Real r[1, 3];
  Real s;
equation
  for i in 1:size(r, 2) loop
    r[1, i] = i * time;
  end for;
  s = sum(r);
end SizeOfVariables;
