// expect: E2035 @10:15
// The inner component must be a subtype of the outer one.
model World
  parameter Real g = 9.81;
end World;
model Other
  parameter Real h = 1;
end Other;
model C
  outer World world;
  Real a = world.g;
end C;
model M
  inner Other world;
  C c;
end M;
