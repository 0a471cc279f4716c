// Two outers of one class without inner: one inner is created (a warning, not an error).
model World
  parameter Real g = 9.81;
end World;
model C
  outer World world;
  Real a = world.g;
end C;
model M
  C c1;
  C c2;
end M;
