model PenaltyBall "A ball on a stiff penalty floor (k = 1e8) with a damper that never pulls"
  parameter Real m = 1 "Mass";
  parameter Real g = 9.81 "Gravity";
  parameter Real k = 1e8 "Contact stiffness";
  parameter Real d = 200 "Contact damping";
  Real h(start = 1, fixed = true) "Height of the ball's lowest point";
  Real v(start = 0, fixed = true) "Velocity";
  Real F "Contact force";
  Real E "Mechanical energy including the spring";
equation
  der(h) = v;
  m*der(v) = F - m*g;
  F = if h < 0 then max(0, -k*h - d*v) else 0;
  E = 0.5*m*v^2 + m*g*h + (if h < 0 then 0.5*k*h^2 else 0);
  annotation(experiment(StopTime = 3, Tolerance = 1e-6));
end PenaltyBall;
