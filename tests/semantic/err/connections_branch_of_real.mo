// expect: E2036 @10:22, E2036 @10:29
// Connections.branch of variables of a predefined type.
connector Frame
  Real phi;
  flow Real tau;
end Frame;
model M
  Frame a, b;
equation
  Connections.branch(a.phi, b.phi);
end M;
