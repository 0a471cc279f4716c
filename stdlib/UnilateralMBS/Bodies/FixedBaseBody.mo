within UnilateralMBS.Bodies;
model FixedBaseBody "Base body fixed in AF, e.g. the horizontal plane (not printed in the paper; reconstructed from spec A.3)"
  // reconstructed: the paper's example uses an object HorizontalSurface (Figure 4.1)
  // whose class is not printed. The base never moves and ignores forces and impulses
  // (infinite mass), so all its velocity increments are zero.
  parameter SI.Position r0[3] = zeros(3) "Position of the body frame origin, AF";
  parameter Real T0[3, 3] = identity(3) "Rotation matrix body frame -> AF";
  output Interfaces.KinematicPortImpacts OutPort "Kinematics of the base (output to constraints)";
  input Interfaces.WrenchPortImpacts InPort1 "Reaction from a constraint (ignored)";
equation
  OutPort.r = r0;
  OutPort.T = T0;
  OutPort.v = zeros(3);
  OutPort.omega = zeros(3);
  OutPort.a = zeros(3);
  OutPort.epsilon = zeros(3);
  OutPort.Deltav = zeros(3);
  OutPort.Deltaomega = zeros(3);
end FixedBaseBody;
