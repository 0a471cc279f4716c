model BouncingBall "A ball dropped from h = 10 m bouncing with restitution e = 0.8"
  parameter Real g = 9.81 "Gravity";
  parameter Real e = 0.8 "Coefficient of restitution";
  parameter Real h0 = 10 "Drop height";
  Real h(start = h0, fixed = true) "Height";
  Real v(start = 0, fixed = true) "Velocity";
  discrete Integer bounces(start = 0, fixed = true);
equation
  der(h) = v;
  der(v) = -g;
  when h < 0 then
    reinit(v, -e*pre(v));
    bounces = pre(bounces) + 1;
  end when;
  annotation(experiment(StopTime = 12, Tolerance = 1e-6));
end BouncingBall;
