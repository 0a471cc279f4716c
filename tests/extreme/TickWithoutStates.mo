model TickWithoutStates "integer(time/period) in a model without states: the when on change(tick) fires"
  parameter Real period = 0.1;
  Integer tick = integer(time/period);
  discrete Integer count(start = 0, fixed = true);
equation
  when change(tick) then
    count = pre(count) + 1;
  end when;
  annotation(experiment(StopTime = 0.95));
end TickWithoutStates;
