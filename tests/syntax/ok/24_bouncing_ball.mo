// A realistic hybrid model: a ball bouncing on the ground.
within;

model BouncingBall "Ball bouncing on the ground with energy loss"
  type Height = Real(unit = "m");
  type Velocity = Real(unit = "m/s");

  parameter Real e(min = 0, max = 1) = 0.7 "Coefficient of restitution";
  parameter Real g = 9.81 "Gravity acceleration";
  parameter Height h0 = 1.0 "Initial height";
  parameter Velocity vSmall = 1e-2 "Below this impact speed the ball stops";

  Height h(start = h0, fixed = true) "Height of the ball";
  Velocity v(start = 0, fixed = true) "Vertical velocity";
  Boolean flying(start = true, fixed = true) "True while the ball is flying";
  Boolean impact "True while the ball touches the ground";
  discrete Velocity v_new "Velocity after an impact";
  discrete Integer bounces(start = 0, fixed = true) "Number of bounces";
  Real energy "Specific mechanical energy";
equation
  impact = h <= 0.0;
  der(h) = v;
  der(v) = if flying then -g else 0;
  energy = g * h + 0.5 * v ^ 2;

  when {h <= 0.0 and v <= 0.0, impact} then
    v_new = if edge(impact) then -e * pre(v) else 0;
    flying = v_new > vSmall;
    reinit(v, v_new);
    bounces = pre(bounces) + 1;
  end when;

  annotation(
    experiment(StartTime = 0, StopTime = 3, Tolerance = 1e-6, Interval = 0.01),
    Documentation(info = "<html><p>The classic bouncing ball example.</p></html>"));
end BouncingBall;
