// An outer component whose inner is two levels up.
model World
  parameter Real g = 9.81;
end World;
model Body
  outer World world;
  Real a = -world.g;
end Body;
model Group
  Body b;
end Group;
model M
  inner World world;
  Group grp;
end M;
