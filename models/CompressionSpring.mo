model CompressionSpring "Paper B's dynamically loaded compression spring: coils as rigid discs joined by spring-dampers, 200 N on the top cap for 0.01 s"
  import Unimo.Collision.*;
  parameter Integer n = 8 "Coils above the fixed bottom coil (the last one is the cap)";
  parameter Real radius = 0.02 "Coil radius";
  parameter Real wire = 0.004 "Wire diameter (disc thickness)";
  parameter Real pitch = 0.01 "Free distance between coil centres";
  parameter Real mc = 0.02 "Mass of a coil";
  parameter Real mCap = 0.5 "Mass of the cap (the last coil)";
  parameter Real k = 2e4 "Stiffness between neighbouring coils";
  parameter Real d = 0.5 "Damping between neighbouring coils";
  parameter Real F = 200 "Load on the cap";
  parameter Real tLoad = 0.01 "Duration of the load";
  // Discs: the cylinder axis (body y) turned onto world z.
  parameter Real Rz[3, 3] = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
  inner CollisionWorld world(g = {0, 0, 0}, K = 1e7, n = 1, law = DampingLaw.Clipped, D = 1e3);
  Obstacle base(shape = ShapeType.Cylinder, dims = {radius, wire, 0}, r0 = {0, 0, 0}, R0 = Rz);
  // Coils guided along the axis (paper B's coils move axially).
  TranslatingBody coil[n](each shape = ShapeType.Cylinder, each dims = {radius, wire, 0},
    m = {if i == n then mCap else mc for i in 1:n}, r0 = {{0, 0, i * pitch} for i in 1:n}, each R0 = Rz);
  Real zs[n + 1] "Heights, base first";
  Real vs[n + 1] "Velocities, base first";
  Real s[n] = {k * (zs[i + 1] - zs[i] - pitch) + d * (vs[i + 1] - vs[i]) for i in 1:n}
    "Spring forces between neighbours (tension positive)";
  Real load = if time < tLoad then F else 0 "Force pushing the cap down";
  Real length = coil[n].r[3] "Height of the cap";
  Real gapMin = min(zs[i + 1] - zs[i] for i in 1:n) - wire "Smallest gap between neighbouring coils";
equation
  zs[1] = 0;
  vs[1] = 0;
  for i in 1:n loop
    zs[i + 1] = coil[i].r[3];
    vs[i + 1] = coil[i].v[3];
  end for;
  for i in 1:n - 1 loop
    coil[i].f = {0, 0, s[i + 1] - s[i]};
  end for;
  coil[n].f = {0, 0, -s[n] - load};
  annotation(experiment(StopTime = 0.1, Tolerance = 1e-4, Interval = 1e-4));
end CompressionSpring;
