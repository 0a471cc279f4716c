// inner / outer components and parameters, including 'inner outer'.
model World "Global environment shared through inner/outer"
  parameter Real g = 9.81 "Gravity";
  parameter Real T_ambient = 293.15 "Ambient temperature";
end World;

model FallingBody "Reads gravity and air density from its environment"
  outer World world;
  outer parameter Real airDensity;
  parameter Real m = 1 "Mass";
  parameter Real cdA = 0.05 "Drag coefficient times area";
  Real h(start = 100, fixed = true) "Height";
  Real v(start = 0, fixed = true) "Velocity";
equation
  der(h) = v;
  m * der(v) = -m * world.g - 0.5 * airDensity * cdA * v * abs(v);
end FallingBody;

model Cluster "Passes the outer world on to its own children"
  inner outer World world;
  FallingBody light(m = 0.1);
  FallingBody heavy(m = 10);
end Cluster;

model Drop "Top level provides the inner elements"
  inner World world(g = 9.80665);
  inner parameter Real airDensity = 1.2;
  FallingBody body;
  Cluster cluster;
  Real ambient = world.T_ambient;
  annotation(experiment(StopTime = 4));
end Drop;
