within UnilateralMBS.Interfaces;
connector KinematicPort "Kinematic state of a rigid body frame, resolved in AF (author's earlier library; not printed in the paper)"
  // reconstructed: the paper uses this base connector from [1] without printing it.
  // No flow variables: causality is given by input/output prefixes where the connector is
  // used (output on bodies, input on constraints), see Interfaces package documentation.
  SI.Position r[3] "Position of the body frame origin (centre of mass) in AF";
  Real T[3, 3] "Rotation matrix body frame -> AF";
  SI.Velocity v[3] "Velocity of the body frame origin in AF";
  SI.AngularVelocity omega[3] "Angular velocity of the body, resolved in AF";
  SI.Acceleration a[3] "Acceleration of the body frame origin in AF";
  SI.AngularAcceleration epsilon[3] "Angular acceleration of the body, resolved in AF";
end KinematicPort;
