model Tunnel "A 5 cm ball at 100 m/s against a 1 cm plate: it must bounce, not pass"
  import Unimo.Collision.*;
  inner CollisionWorld world(g = {0, 0, 0}, K = 1e9, n = 1.5, law = DampingLaw.Flores, e = 0.9);
  Ball ball(radius = 0.025, m = 0.5, r0 = {0, 0, 1}, v0 = {0, 0, -100});
  Obstacle plate(shape = ShapeType.Box, dims = {0.5, 0.5, 0.01});
  annotation(experiment(StopTime = 0.05));
end Tunnel;
