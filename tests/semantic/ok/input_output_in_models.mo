// Inputs and outputs in models and blocks, bound or connected.
block B
  input Real u;
  output Real y;
equation
  y = 2*u;
end B;
model M
  B b(u = 1);
  Real z = b.y;
end M;
