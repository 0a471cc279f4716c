model CyclicParameters
  parameter Integer a = b + 1;
  parameter Integer b = a * 2;
  Real x[a];
equation
  x = zeros(a);
end CyclicParameters;
