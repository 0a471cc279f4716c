within UnilateralMBS.Bodies;
model FixedBaseBodyNPorts "Base body fixed in AF with nPorts constraint ports, e.g. a table touched by several bodies (added; not in the paper)"
  // added (not in the paper): FixedBaseBody with one kinematic/wrench port pair per
  // constraint. Infinite mass: forces and impulses are ignored, increments are zero.
  parameter Integer nPorts = 1 "Number of constraint ports";
  parameter SI.Position r0[3] = zeros(3) "Position of the body frame origin, AF";
  parameter Real T0[3, 3] = identity(3) "Rotation matrix body frame -> AF";
  output Interfaces.KinematicPortImpacts OutPorts[nPorts] "Kinematics of the base (output to constraints)";
  input Interfaces.WrenchPortImpacts InPorts[nPorts] "Reactions from the constraints (ignored)";
equation
  for i in 1:nPorts loop
    OutPorts[i].r = r0;
    OutPorts[i].T = T0;
    OutPorts[i].v = zeros(3);
    OutPorts[i].omega = zeros(3);
    OutPorts[i].a = zeros(3);
    OutPorts[i].epsilon = zeros(3);
    OutPorts[i].Deltav = zeros(3);
    OutPorts[i].Deltaomega = zeros(3);
  end for;
end FixedBaseBodyNPorts;
