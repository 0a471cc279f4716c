model TenThousandEvents "a sawtooth reset every 1e-3: 10,000 state events in 10 s"
  Real x(start = 0, fixed = true);
  discrete Integer resets(start = 0, fixed = true);
equation
  der(x) = 1;
  when x >= 1e-3 then
    reinit(x, 0);
    resets = pre(resets) + 1;
  end when;
  annotation(experiment(StopTime = 10.0005));
end TenThousandEvents;
