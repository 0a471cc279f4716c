model StiffTracking "A fast first-order lag tracking a slow sine: stiff once the transient has died out"
  Real x(start = 0, fixed = true);
equation
  der(x) = -1e4 * (x - sin(time));
  annotation(experiment(StopTime = 1, Tolerance = 1e-6));
end StiffTracking;
