model SampleCounter
  discrete Integer count(start = 0, fixed = true);
  Real x(start = 0, fixed = true);
equation
  der(x) = 1;
  when sample(0.05, 0.1) then
    count = pre(count) + 1;
  end when;
  annotation(experiment(StopTime = 1));
end SampleCounter;
