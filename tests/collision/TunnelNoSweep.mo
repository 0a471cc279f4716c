model TunnelNoSweep "Tunnel without the sweep test: the ball passes through the plate (paper B's ghosting)"
  import Unimo.Collision.*;
  inner CollisionWorld world(g = {0, 0, 0}, K = 1e9, n = 1.5, law = DampingLaw.Flores, e = 0.9, sweep = false);
  Ball ball(radius = 0.025, m = 0.5, r0 = {0, 0, 1}, v0 = {0, 0, -100});
  Obstacle plate(shape = ShapeType.Box, dims = {0.5, 0.5, 0.01});
  annotation(experiment(StopTime = 0.05));
end TunnelNoSweep;
