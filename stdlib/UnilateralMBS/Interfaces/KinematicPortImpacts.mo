within UnilateralMBS.Interfaces;
connector KinematicPortImpacts "Kinematic port that also carries velocity increments at impacts"
  extends KinematicPort;
  SI.Velocity Deltav[3] "Increment of the centre of mass velocity at an impact, AF";
  SI.AngularVelocity Deltaomega[3] "Increment of the angular velocity at an impact, AF";
end KinematicPortImpacts;
