within UnilateralMBS.Bodies;
partial model RigidBodyImpactsAcausal "Rigid body that applies its own velocity increments at impacts (acausal approach)"
  // The paper declares this class as `model`; it is `partial` here because F1, M1,
  // ImpactForce1 and ImpactTorque1 are still left to derived classes, so it is not locally
  // balanced (a non-partial model must be, MLS section 4.7).
  extends RigidBodyImpacts;
equation
  when Impact then
    reinit(v, v + Deltav);
    reinit(omega, omega + Deltaomega);
  end when;
end RigidBodyImpactsAcausal;
