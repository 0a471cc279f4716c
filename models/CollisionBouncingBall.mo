model CollisionBouncingBall "A ball dropped on a floor through the collision world (penalty contact)"
  import Unimo.Collision.*;
  inner CollisionWorld world(K = 1e7, n = 1.5, law = DampingLaw.HuntCrossley, e = 0.8);
  Ball ball(radius = 0.1, m = 1, r0 = {0, 0, 1});
  Obstacle floor(shape = ShapeType.HalfSpace);
  annotation(experiment(StopTime = 3, Tolerance = 1e-6, Interval = 0.01));
end CollisionBouncingBall;
