model Dahlquist "Dahlquist's test equation y' = lambda*y with lambda = -1e6: very stiff"
  parameter Real lambda = -1e6;
  Real y(start = 1, fixed = true);
equation
  der(y) = lambda*y;
  annotation(experiment(StopTime = 1, Tolerance = 1e-6));
end Dahlquist;
