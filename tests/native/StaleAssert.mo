model StaleAssert "An assertion on a value the plan computes, checked after every solver step: after a native right-hand side the plan must run again first"
  Real x(start = 0, fixed = true);
  Real lag "computed by the plan's one step";
equation
  der(x) = 1 + 0.5*sin(10*time);
  lag = time - x;
  // Not the plan's expression (a different sum), so the assertion's tape reads lag;
  // without events, so no zero crossing runs the plan at the end of each step.
  assert(noEvent(abs(lag + x - time) < 1e-9), "lag is not time - x");
  annotation(experiment(StopTime = 2, Interval = 1));
end StaleAssert;
