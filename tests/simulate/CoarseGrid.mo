model CoarseGrid "An oscillation of period 0.63 on an output grid of 0.5"
  Real x(start = 1, fixed = true);
  Real v(start = 0, fixed = true);
equation
  der(x) = v;
  der(v) = -100 * x;
  annotation(experiment(StopTime = 3, Interval = 0.5));
end CoarseGrid;
