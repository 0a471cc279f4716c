// expect: E2022 @8:19
model World
protected
  parameter Real g = 9.81;
end World;
model Body
  outer World world;
  Real a = -world.g;
end Body;
