within UnilateralMBS.Interfaces;
connector WrenchPortImpacts "Wrench port that also carries impact impulses"
  extends WrenchPort;
  SI.Impulse ImpactForce[3] "Impulse acting on the body at point P, AF";
  SI.AngularImpulse ImpactTorque[3] "Angular impulse acting on the body about point P, AF";
end WrenchPortImpacts;
