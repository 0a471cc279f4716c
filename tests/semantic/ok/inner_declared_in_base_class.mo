// An inner declared in a base class is visible to the components of the derived class.
model World
  parameter Real g = 9.81;
end World;
model C
  outer World world;
  Real a = world.g;
end C;
partial model Base
  inner World world(g = 1.62);
end Base;
model M
  extends Base;
  C c;
end M;
