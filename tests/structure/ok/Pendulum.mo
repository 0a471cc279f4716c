model Pendulum "Cartesian pendulum: index 3"
  parameter Real L = 1 "Length";
  parameter Real m = 1 "Mass";
  parameter Real g = 9.81 "Gravity";
  Real x(start = 0.6, fixed = true);
  Real y(start = -0.8);
  Real vx(start = 0, fixed = true);
  Real vy;
  Real F "Rod force per length";
equation
  der(x) = vx;
  der(y) = vy;
  m*der(vx) = -F*x;
  m*der(vy) = -F*y - m*g;
  x^2 + y^2 = L^2;
  annotation(experiment(StopTime = 5));
end Pendulum;
