// A Boolean defined by sample() is true at the instants only: `when trig` fires at
// every instant, like `when sample(...)` (it fired once: trig kept its value 1 after
// the first instant, so later instants were no edge).
model SampleDefinedBoolean
  Boolean trig;
  Integer n(start = 0, fixed = true);
  Integer m(start = 0, fixed = true);
equation
  trig = sample(0.1, 0.1);
  when trig then
    n = pre(n) + 1;
  end when;
  when sample(0.1, 0.1) then
    m = pre(m) + 1;
  end when;
  annotation(experiment(StopTime = 1));
end SampleDefinedBoolean;
