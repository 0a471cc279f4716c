// `--vars x`: the relation `x > 0.5` is held only by the equation of `above`, which
// nothing asked for needs, so it is no zero crossing and makes no events; the loop of
// `z` and `w` goes too. Asked for `x` and `above`, both stay.
model PruneLeavesOutEvents
  Real x(start = 1, fixed = true);
  Real above "1 while x > 0.5";
  Real z;
  Real w;
equation
  der(x) = -x + sin(10 * time);
  above = if x > 0.5 then 1 else 0;
  z + w ^ 3 = x;
  w - z = time;
end PruneLeavesOutEvents;
