model Tumble "Every shape of the collision library: a ball, a box and an ellipsoid fall on a floor; a cylinder, a cone and a capsule stand by"
  import Unimo.Collision.*;
  inner CollisionWorld world(K = 1e5, n = 1, law = DampingLaw.Clipped, D = 200, muStatic = 0, muSliding = 0);
  Ball ball(radius = 0.1, m = 1, r0 = {0, 0, 0.6}, v0 = {0.5, 0, 0});
  RigidBody box(shape = ShapeType.Box, dims = {0.3, 0.15, 0.1}, m = 1, I = {0.0027, 0.0083, 0.0094},
    r0 = {0.6, 0, 0.5}, w0 = {2, 3, 0}, f = zeros(3), t = zeros(3));
  RigidBody egg(shape = ShapeType.Ellipsoid, dims = {0.15, 0.1, 0.08}, m = 1, I = {0.0066, 0.0116, 0.013},
    r0 = {-0.6, 0, 0.4}, w0 = {0, 4, 1}, f = zeros(3), t = zeros(3));
  Obstacle floor(shape = ShapeType.HalfSpace, dims = {0, 0, 0});
  // Axes (body y) turned onto world z: R0 maps body y to z.
  Obstacle pillar(shape = ShapeType.Cylinder, dims = {0.05, 0.3, 0}, r0 = {0, 0.6, 0.15},
    R0 = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}});
  Obstacle spike(shape = ShapeType.Cone, dims = {0.08, 0.25, 0}, r0 = {0.6, 0.6, 0.125},
    R0 = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}});
  Obstacle post(shape = ShapeType.Capsule, dims = {0.05, 0.2, 0}, r0 = {-0.6, 0.6, 0.15},
    R0 = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}});
  annotation(experiment(StopTime = 1, Tolerance = 1e-6, Interval = 0.01));
end Tumble;
