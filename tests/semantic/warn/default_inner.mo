model World
  parameter Real g = 9.81;
end World;
model Body
  outer World world;
  Real v(start = 0, fixed = true);
equation
  der(v) = -world.g;
end Body;
model M
  Body b1;
  Body b2;
end M;
