// Realistic mechanical models: a pendulum as an index-3 DAE in Cartesian
// coordinates, and a damped pendulum in angle form.
within;

model Pendulum "Planar pendulum in Cartesian coordinates"
  parameter Real m = 1 "Mass";
  parameter Real L = 1 "Rod length";
  parameter Real g = 9.81 "Gravity";
  parameter Real phi0 = 0.5 "Initial angle";
  Real x(start = L * sin(phi0), fixed = true, stateSelect = StateSelect.prefer) "Horizontal position";
  Real y(start = -L * cos(phi0), stateSelect = StateSelect.prefer) "Vertical position";
  Real vx(start = 0, fixed = true) "Horizontal velocity";
  Real vy "Vertical velocity";
  Real lambda "Rod force divided by length";
  Real phi "Angle from the vertical";
equation
  der(x) = vx;
  der(y) = vy;
  m * der(vx) = -lambda * x;
  m * der(vy) = -lambda * y - m * g;
  x ^ 2 + y ^ 2 = L ^ 2;
  phi = atan2(x, -y);
  annotation(experiment(StartTime = 0, StopTime = 5, Tolerance = 1e-6, Interval = 0.01));
end Pendulum;

model DampedPendulum "Pendulum in angle coordinates with viscous damping"
  parameter Real L = 1;
  parameter Real g = 9.81;
  parameter Real d = 0.1 "Damping coefficient";
  Real phi(start = 0.5, fixed = true, stateSelect = StateSelect.always) "Angle";
  Real w(start = 0, fixed = true) "Angular velocity";
  Real[2] pos "Bob position";
  Real energy "Specific energy";
equation
  der(phi) = w;
  der(w) = -g / L * sin(phi) - d * w;
  pos = {L * sin(phi), -L * cos(phi)};
  energy = 0.5 * L ^ 2 * w ^ 2 + g * L * (1 - cos(phi));
  annotation(experiment(StopTime = 10));
end DampedPendulum;
