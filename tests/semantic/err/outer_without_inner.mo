// expect: E2013 @6:15
model World
  parameter Real g = 9.81;
end World;
model M
  outer World world;
  Real a = world.g;
end M;
