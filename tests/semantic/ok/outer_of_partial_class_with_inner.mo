// An outer of a partial class is fine when a non-partial inner is found.
partial model Environment
  parameter Real T = 293;
end Environment;
model Air
  extends Environment;
end Air;
model C
  outer Environment env;
  Real t = env.T;
end C;
model M
  inner Air env;
  C c;
end M;
