// The inner may have more elements than the outer's class: it is a subtype.
model World
  parameter Real g = 9.81;
end World;
model BigWorld
  extends World;
  parameter Real rho = 1.2;
end BigWorld;
model C
  outer World world;
  Real a = world.g;
end C;
model M
  inner BigWorld world;
  C c;
end M;
