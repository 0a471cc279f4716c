model StartStopEvents "sample instants at the start and at the stop time, initial()"
  discrete Integer n(start = 0, fixed = true);
  discrete Integer inits(start = 0, fixed = true);
  Real x(start = 0, fixed = true);
equation
  der(x) = 1;
  when sample(0, 0.25) then
    n = pre(n) + 1;
  end when;
  when initial() then
    inits = pre(inits) + 1;
  end when;
  annotation(experiment(StopTime = 1));
end StartStopEvents;
