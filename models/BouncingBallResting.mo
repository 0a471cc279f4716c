model BouncingBallResting "The bouncing ball with a resting guard: it comes to rest at the Zeno time and stays"
  parameter Real g = 9.81 "Gravity";
  parameter Real e = 0.8 "Coefficient of restitution";
  parameter Real h0 = 10 "Drop height";
  parameter Real vSmall = 1e-6 "Impact speed below which the ball rests";
  Real h(start = h0, fixed = true) "Height";
  Real v(start = 0, fixed = true) "Velocity";
  Boolean resting(start = false, fixed = true);
  discrete Integer bounces(start = 0, fixed = true);
equation
  der(h) = v;
  der(v) = if resting then 0 else -g;
  when h < 0 then
    reinit(v, if -pre(v) < vSmall then 0 else -e*pre(v));
    reinit(h, 0);
    resting = -pre(v) < vSmall;
    bounces = pre(bounces) + 1;
  end when;
  annotation(experiment(StopTime = 20, Tolerance = 1e-8));
end BouncingBallResting;
