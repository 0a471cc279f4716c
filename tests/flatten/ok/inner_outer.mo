model World "shared environment"
  parameter Real g = 9.81;
end World;

model Body
  outer World world;
  parameter Real gLocal = world.g "a parameter bound through the outer";
  Real h(start = 1, fixed = true), v(start = 0, fixed = true);
equation
  der(h) = v;
  der(v) = -gLocal;
end Body;

model Cluster "inner of its own: bodies inside see the cluster's world"
  inner World world(g = 3.71);
  Body b;
end Cluster;

model InnerOuter "one inner, many outers, and a nested inner that shadows it"
  inner World world(g = 1.62);
  Body b1, b2;
  Cluster mars;
end InnerOuter;
