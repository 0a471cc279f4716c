model CylinderOnBox "A cylinder lying on a box under gravity: a line contact that must stay at rest"
  import Unimo.Collision.*;
  inner CollisionWorld world(K = 1e7, n = 1, law = DampingLaw.Clipped, D = 2e4, muStatic = 0.5, muSliding = 0.4, vSwitch = 1e-3);
  parameter Real radius = 0.05;
  parameter Real length = 0.4;
  parameter Real m = 2;
  // Placed at rest: the pair's spring carries the weight, K delta = m g (one law per
  // pair, shared by the points of the line contact).
  // Axis along world x: the body y axis (the cylinder's axis) turned onto x.
  RigidBody cylinder(shape = ShapeType.Cylinder, dims = {radius, length, 0}, m = m,
    I = {m * (3 * radius ^ 2 + length ^ 2) / 12, m * radius ^ 2 / 2, m * (3 * radius ^ 2 + length ^ 2) / 12},
    r0 = {0, 0, 0.1 + radius - m * 9.81 / 1e7},
    R0 = {{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}}, f = zeros(3), t = zeros(3));
  Obstacle table(shape = ShapeType.Box, dims = {1, 1, 0.2}, r0 = {0, 0, 0});
  annotation(experiment(StopTime = 10, Tolerance = 1e-6, Interval = 0.01));
end CylinderOnBox;
