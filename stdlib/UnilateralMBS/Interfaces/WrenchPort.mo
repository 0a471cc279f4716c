within UnilateralMBS.Interfaces;
connector WrenchPort "Force and torque acting on a body at a point, resolved in AF (author's earlier library; not printed in the paper)"
  // reconstructed: the paper uses Port.F, Port.M and Port.P of this connector from [1].
  // F and M are potentials, not flows: F is the force ON the body at the receiving end
  // (see Interfaces package documentation for the causality convention).
  SI.Force F[3] "Force acting on the body, AF";
  SI.Torque M[3] "Torque acting on the body about point P, AF";
  SI.Position P[3] "Point where the force F acts, AF";
end WrenchPort;
