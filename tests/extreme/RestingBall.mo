model RestingBall "the resting rule of issue 15: after the last bounce v stays exactly 0"
  parameter Real g = 9.81;
  parameter Real e = 0.8;
  parameter Real vmin = 1e-6;
  Real h(start = 10, fixed = true);
  Real v(start = 0, fixed = true);
  Boolean flying(start = true, fixed = true);
  discrete Integer bounces(start = 0, fixed = true);
equation
  der(h) = v;
  der(v) = if flying then -g else 0;
  when h <= 0 and v < 0 then
    flying = -e*pre(v) >= vmin;
    reinit(v, if flying then -e*pre(v) else 0);
    bounces = pre(bounces) + 1;
  end when;
  annotation(experiment(StopTime = 20));
end RestingBall;

model RestingBallTiny "the resting speed far below what the tolerances resolve"
  extends RestingBall(vmin = 1e-9);
end RestingBallTiny;
