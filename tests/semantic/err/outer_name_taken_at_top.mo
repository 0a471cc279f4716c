// expect: E2013 @7:15
model World
  parameter Real g = 9.81;
end World;
// The model's own `world` is not inner: no inner can be added beside it.
model C
  outer World world;
  Real a = world.g;
end C;
model M
  parameter Real world = 1;
  C c;
end M;
