model SqrtOfNegative "y becomes NaN after t = 1"
  Real x(start = 1, fixed = true);
  Real y;
equation
  der(x) = -1;
  y = sqrt(x);
  annotation(experiment(StopTime = 2));
end SqrtOfNegative;
