model ComputedPlacement "A collision body placed by a variable the model computes: refused"
  import Unimo.Collision.*;
  inner CollisionWorld world;
  Real x(start = 1, fixed = true);
  Real height;
  CollisionBody probe(r = {0, 0, height}, R = identity(3), v = zeros(3), w = zeros(3));
  Obstacle floor(shape = ShapeType.HalfSpace);
equation
  der(x) = -x;
  height = sin(x) + x ^ 3;
end ComputedPlacement;
