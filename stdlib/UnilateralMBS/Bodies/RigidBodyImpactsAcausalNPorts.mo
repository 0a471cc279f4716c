within UnilateralMBS.Bodies;
partial model RigidBodyImpactsAcausalNPorts "Rigid body with nPorts constraint ports (kinematics, wrench, impact signal per port) that applies its own velocity increments at impacts (added; not in the paper)"
  // added (not in the paper): RigidBodyImpacts has one wrench port and one impact signal;
  // a body touched by several constraints needs one port triple per constraint:
  //   connect(body.OutPorts[i], c.InPortA);  connect(c.OutPortA, body.InPorts[i]);
  //   connect(c.OutImpactSignalA, body.InImpactSignals[i]);   (or ...B for side B)
  // Forces and torques of all ports are summed as in RigidBodyImpacts.
  //
  // Impulses. A constraint of this library solves its impulse equations at all times,
  // Newton's law (DeltavrA - DeltavrB)*normA = -(1 + k)*relvn included, and the body
  // applies the increments only when Impact is true. With one constraint per body that is
  // harmless. With several, summing every port's impulse would apply, at the impact of
  // constraint i, also the "would-be" impulses of every other constraint on the body. So:
  //  - the body's increments Deltav, Deltaomega sum only the impulses of the ports whose
  //    impact signal is true (at an instant without impact they are zero);
  //  - port i sends back to its constraint the body's increments if its signal is true
  //    (simultaneous impacts at one instant are then coupled through the body), else the
  //    increments that its own impulse alone would cause (DeltavPort, DeltaomegaPort):
  //    the constraint keeps solving a private, regular impulse problem that is not used.
  // Not handled (as in the paper, "indirect impacts"): an impulse through a constraint
  // that is in contact (Sliding/Rolling) at that instant.
  extends RigidBody;
  parameter Integer nPorts = 1 "Number of constraint ports";
  output Interfaces.KinematicPortImpacts OutPorts[nPorts] "Kinematics of the body, one port per constraint";
  input Interfaces.WrenchPortImpacts InPorts[nPorts] "Wrench and impulses from the constraints";
  Modelica.Blocks.Interfaces.BooleanInPort InImpactSignals[nPorts] "Impact signals from the constraints";
  SI.Velocity Deltav[3] "Increment of the centre of mass velocity at an impact, AF";
  SI.AngularVelocity Deltaomega[3] "Increment of the angular velocity at an impact, body frame";
  SI.Velocity DeltavPort[nPorts, 3] "Increment of v that the impulse of port i alone causes, AF";
  SI.AngularVelocity DeltaomegaPort[nPorts, 3] "Increment of omega that the impulse of port i alone causes, body frame";
  SI.Force FPort[nPorts, 3] "Force of port i, AF";
  SI.Torque MPort[nPorts, 3] "Torque of port i about the centre of mass, AF";
  SI.AngularImpulse LPort[nPorts, 3] "Angular impulse of port i about the centre of mass, AF";
  SI.Impulse SGated[nPorts, 3] "Impulse of port i if its impact signal is true, else 0, AF";
  SI.AngularImpulse LGated[nPorts, 3] "Angular impulse of port i if its impact signal is true, else 0, AF";
  Boolean Impact "True at the instant of an impact on any port";
  Boolean PortImpact[nPorts] "Impact signal of port i";
  SI.Impulse ImpactForce1[3] "Additional impulse from derived classes, AF";
  SI.AngularImpulse ImpactTorque1[3] "Additional angular impulse about the centre of mass from derived classes, AF";
  SI.Force F1[3] "Additional force from derived classes (e.g. gravity), AF";
  SI.Torque M1[3] "Additional torque about the centre of mass from derived classes, AF";
equation
  for i in 1:nPorts loop
    PortImpact[i] = InImpactSignals[i].signal[1];
    FPort[i, :] = InPorts[i].F;
    MPort[i, :] = InPorts[i].M + cross(InPorts[i].P - r, InPorts[i].F);
    LPort[i, :] = InPorts[i].ImpactTorque + cross(InPorts[i].P - r, InPorts[i].ImpactForce);
    SGated[i, :] = if InImpactSignals[i].signal[1] then InPorts[i].ImpactForce else zeros(3);
    LGated[i, :] = if InImpactSignals[i].signal[1] then LPort[i, :] else zeros(3);
    m*DeltavPort[i, :] = InPorts[i].ImpactForce;
    I*DeltaomegaPort[i, :] = transpose(T)*LPort[i, :];
    OutPorts[i].r = r;
    OutPorts[i].T = T;
    OutPorts[i].v = v;
    OutPorts[i].omega = T*omega;
    OutPorts[i].a = a;
    OutPorts[i].epsilon = T*epsilon;
    OutPorts[i].Deltav = if InImpactSignals[i].signal[1] then Deltav else DeltavPort[i, :];
    OutPorts[i].Deltaomega = T*(if InImpactSignals[i].signal[1] then Deltaomega else DeltaomegaPort[i, :]);
  end for;
  F = F1 + {sum(FPort[i, j] for i in 1:nPorts) for j in 1:3};
  M = M1 + {sum(MPort[i, j] for i in 1:nPorts) for j in 1:3};
  m*Deltav = ImpactForce1 + {sum(SGated[i, j] for i in 1:nPorts) for j in 1:3};
  I*Deltaomega = transpose(T)*(ImpactTorque1 + {sum(LGated[i, j] for i in 1:nPorts) for j in 1:3});
  // OutPort of RigidBody is not used by constraints here (the OutPorts carry Deltav)
algorithm
  Impact := false;
  for i in 1:nPorts loop
    Impact := Impact or PortImpact[i];
  end for;
equation
  when Impact then
    reinit(v, v + Deltav);
    reinit(omega, omega + Deltaomega);
  end when;
end RigidBodyImpactsAcausalNPorts;
