within UnilateralMBS.Bodies;
partial model RigidBodyImpacts "Rigid body with one wrench port and the impact equations (2.6)"
  extends RigidBody(redeclare output Interfaces.KinematicPortImpacts OutPort);
  SI.Velocity Deltav[3] "Increment of the centre of mass velocity at an impact, AF";
  SI.AngularVelocity Deltaomega[3] "Increment of the angular velocity at an impact, body frame";
  SI.Impulse ImpactForce1[3] "Additional impulse from derived classes, AF";
  SI.AngularImpulse ImpactTorque1[3] "Additional angular impulse about the centre of mass from derived classes, AF";
  Boolean Impact "True at the instant of an impact";
  SI.Force F1[3] "Additional force from derived classes (e.g. gravity), AF";
  SI.Torque M1[3] "Additional torque about the centre of mass from derived classes, AF";
  input Interfaces.WrenchPortImpacts InPort1 "Wrench and impulses from a constraint";
  Modelica.Blocks.Interfaces.BooleanInPort InImpactSignal1 "Impact signal from a constraint";
  Modelica.Blocks.Interfaces.BooleanOutPort OutImpactSignal1 "Impact signal emitted by the body (always false)";
equation
  F = InPort1.F + F1;
  M = InPort1.M + cross(InPort1.P - r, InPort1.F) + M1;
  OutImpactSignal1.signal[1] = false;
  Impact = false or InImpactSignal1.signal[1];
  // The paper prints the next two equations twice; they are written once here.
  OutPort.Deltav = Deltav;
  OutPort.Deltaomega = T*Deltaomega;
  // Impact equations (2.6): m*Deltav = S (AF), I*Deltaomega = T (body frame).
  m*Deltav = InPort1.ImpactForce + ImpactForce1;
  // The OCR shows "Deltaomega = transpose(T)*(...)"; the inertia factor I of eq. (2.6) is
  // restored (an angular velocity increment cannot equal an angular impulse).
  I*Deltaomega = transpose(T)*(InPort1.ImpactTorque + cross(InPort1.P - r, InPort1.ImpactForce) + ImpactTorque1);
end RigidBodyImpacts;
