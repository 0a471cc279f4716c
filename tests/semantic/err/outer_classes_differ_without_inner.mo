// expect: E2013 @14:12
// Two outer declarations of one name and different classes: no inner can be created.
model W1
  parameter Real g = 9.81;
end W1;
model W2
  parameter Real g = 1;
end W2;
model C1
  outer W1 world;
  Real a = world.g;
end C1;
model C2
  outer W2 world;
  Real a = world.g;
end C2;
model M
  C1 c1;
  C2 c2;
end M;
