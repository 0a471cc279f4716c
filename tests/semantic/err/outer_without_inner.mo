// expect: E2013 @6:15
partial model World
  parameter Real g = 9.81;
end World;
model M
  outer World world;
  Real a = world.g;
end M;
