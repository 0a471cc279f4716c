model DiscOnDisc "A disc dropped face-on onto a fixed coaxial disc: at rest the pair's spring carries the weight, K delta = m g"
  import Unimo.Collision.*;
  parameter Real radius = 0.02 "Disc radius";
  parameter Real thickness = 0.004 "Disc thickness";
  parameter Real m = 0.5 "Mass of the upper disc";
  parameter Real drop = 1e-4 "Height of the fall";
  // Discs: the cylinder axis (body y) turned onto world z.
  parameter Real Rz[3, 3] = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
  inner CollisionWorld world(g = {0, 0, -9.81}, K = 1e7, n = 1, law = DampingLaw.Clipped, D = 1e3);
  Obstacle base(shape = ShapeType.Cylinder, dims = {radius, thickness, 0}, r0 = {0, 0, 0}, R0 = Rz);
  TranslatingBody disc(shape = ShapeType.Cylinder, dims = {radius, thickness, 0}, m = m,
    r0 = {0, 0, thickness + drop}, R0 = Rz);
  Real depth = thickness - disc.r[3] "Penetration depth";
equation
  disc.f = zeros(3);
  annotation(experiment(StopTime = 0.2));
end DiscOnDisc;
