model AssertAfterThree "A decay whose assertion fails once time passes 3.5"
  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
  assert(time < 3.5, "time is up");
  annotation(experiment(StopTime = 5));
end AssertAfterThree;
