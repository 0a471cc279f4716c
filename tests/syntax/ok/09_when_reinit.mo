// when / elsewhen equations, reinit, pre, edge, change, sample,
// initial(), terminal(), vector conditions and terminate.
model SampledCounter "Counts samples and detects edges"
  parameter Real period = 0.1;
  discrete Integer count(start = 0, fixed = true);
  discrete Real lastSample(start = 0, fixed = true);
  Real x(start = 0, fixed = true);
  Boolean above;
  Boolean rising;
  Boolean counted;
equation
  der(x) = 1;
  above = x > 0.5;
  when sample(0, period) then
    count = pre(count) + 1;
    lastSample = time;
  end when;
  rising = edge(above);
  counted = change(count);
end SampledCounter;

model Hysteresis "Two-point switch with elsewhen"
  parameter Real uLow = -0.5;
  parameter Real uHigh = 0.5;
  Real u = sin(2 * time);
  discrete Boolean on(start = false, fixed = true);
equation
  when u > uHigh then
    on = true;
  elsewhen u < uLow then
    on = false;
  end when;
end Hysteresis;

model ResetIntegrator "reinit of a state variable"
  parameter Integer maxResets = 5;
  Real x(start = 0, fixed = true);
  discrete Integer resets(start = 0, fixed = true);
  discrete Real tEvent;
  discrete Real tEnd(start = 0, fixed = true);
equation
  der(x) = 1;
  when x >= 1 then
    reinit(x, 0);
    resets = pre(resets) + 1;
  end when;
  when {initial(), resets > 2} then
    tEvent = time;
  end when;
  when terminal() then
    tEnd = time;
  end when;
  when resets >= maxResets then
    terminate("maximum number of resets reached");
  end when;
end ResetIntegrator;
