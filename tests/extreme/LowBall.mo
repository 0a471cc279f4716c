model LowBall "the bouncing ball of models/BouncingBall.mo dropped from 1 m: its Zeno time (4.06 s) comes before the stop time"
  parameter Real g = 9.81;
  parameter Real e = 0.8;
  parameter Real h0 = 1;
  Real h(start = h0, fixed = true);
  Real v(start = 0, fixed = true);
  discrete Integer bounces(start = 0, fixed = true);
equation
  der(h) = v;
  der(v) = -g;
  when h < 0 then
    reinit(v, -e*pre(v));
    bounces = pre(bounces) + 1;
  end when;
  annotation(experiment(StopTime = 20));
end LowBall;

model LowBall2 "from 2 m (Zeno time 5.75 s)"
  extends LowBall(h0 = 2);
end LowBall2;

model LowBall5 "from 5 m (Zeno time 9.09 s)"
  extends LowBall(h0 = 5);
end LowBall5;
