model PendulumCartesian "Pendulum in Cartesian coordinates (index 3), states chosen at run time"
  parameter Real L = 1 "Length";
  parameter Real m = 1 "Mass";
  parameter Real g = 9.81 "Gravity";
  parameter Real phi0 = 1.5707963267948966 "Release angle from the downward vertical";
  parameter Real w0 = 0 "Initial angular velocity";
  Real x(start = L*sin(phi0), fixed = true);
  Real y(start = -L*cos(phi0), fixed = true);
  Real vx(start = L*w0*cos(phi0), fixed = true);
  Real vy(start = L*w0*sin(phi0), fixed = true);
  Real F "Rod force per length";
  Real energy = m*(vx^2 + vy^2)/2 + m*g*y;
  Real drift = x^2 + y^2 - L^2;
equation
  der(x) = vx;
  der(y) = vy;
  m*der(vx) = -F*x;
  m*der(vy) = -F*y - m*g;
  x^2 + y^2 = L^2;
  annotation(experiment(StopTime = 100, Tolerance = 1e-8, Interval = 0.02));
end PendulumCartesian;
