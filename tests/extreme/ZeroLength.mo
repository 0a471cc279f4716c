model ZeroLength "start = stop: the result is the initial values"
  parameter Real k = 2;
  Real x(start = 1, fixed = true);
  Real y;
equation
  der(x) = -x;
  y = k*x;
  annotation(experiment(StartTime = 1, StopTime = 1));
end ZeroLength;
