model HeldTimeEvents "integer, floor, ceil, div, mod and rem of time: held between events, events at their bounds"
  parameter Real period = 0.1;
  Integer tick "integer(time/period)";
  discrete Integer changes(start = 0, fixed = true) "events of change(tick)";
  Real saw "mod(time, 0.25)";
  Real q "div(time - 0.55, 0.2)";
  Real r "rem(time - 0.55, 0.2)";
  Real c "ceil(4*time)";
  Real x(start = 0, fixed = true);
equation
  der(x) = 1;
  tick = integer(time/period);
  saw = mod(time, 0.25);
  q = div(time - 0.55, 0.2);
  r = rem(time - 0.55, 0.2);
  c = ceil(4*time);
  when change(tick) then
    changes = pre(changes) + 1;
  end when;
  annotation(experiment(StopTime = 0.95));
end HeldTimeEvents;
