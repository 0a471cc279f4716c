model A
  Real x[3];
equation
  for i in 1:3 loop
    x[j] = i;
  end for;
end A;
