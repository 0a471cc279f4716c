model Stiff1e9 "stiffness ratio 1e9: x follows cos(t) with rate 1e9, y decays with rate 1"
  parameter Real k = 1e9;
  Real x(start = 0, fixed = true);
  Real y(start = 1, fixed = true);
equation
  der(x) = -k*(x - cos(time));
  der(y) = -y;
  annotation(experiment(StopTime = 1));
end Stiff1e9;
