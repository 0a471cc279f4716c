model HugeBody "a ball dropped on a box 1e300 long"
  import Unimo.Collision.*;
  inner CollisionWorld world(K = 1e7, n = 1.5, law = DampingLaw.HuntCrossley, e = 0.8);
  Ball ball(radius = 0.1, m = 1, r0 = {0, 0, 1});
  Obstacle floor(shape = ShapeType.Capsule, dims = {1e300, 0.5, 0.5});
  annotation(experiment(StopTime = 1, Tolerance = 1e-6, Interval = 0.01));
end HugeBody;
