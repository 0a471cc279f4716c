model ArrayParameters "Array parameters set whole from the command line"
  parameter Real g[2] = {1, 2} "A vector";
  parameter Integer m[2, 2] = {{1, 0}, {0, 1}} "A matrix";
  Real x(start = 0, fixed = true);
equation
  der(x) = g[1] + g[2] + m[1, 2];
  annotation(experiment(StopTime = 1));
end ArrayParameters;
