model ArraysAndFor
  parameter Integer n = 4;
  parameter Real k[n] = {1, 2, 3, 4};
  Real x[n](each start = 1, each fixed = true);
  Real total;
equation
  for i in 1:n loop
    der(x[i]) = -k[i] * x[i];
  end for;
  total = sum(x);
end ArraysAndFor;
