within UnilateralMBS.Constraints;
partial model Constraint "Base model of a constraint between bodies A and B"
  parameter Integer ConstraintNo = 1;
  replaceable input Interfaces.KinematicPort InPortA "Kinematics of body A";
  replaceable output Interfaces.WrenchPort OutPortA "Reaction acting on body A";
  replaceable input Interfaces.KinematicPort InPortB "Kinematics of body B";
  replaceable output Interfaces.WrenchPort OutPortB "Reaction acting on body B";
equation
  // reconstructed: the paper elides the equations with dots. Action and reaction, written
  // like the impulse equations the paper prints in ConstraintImpacts (moments taken about
  // the respective points P_A, P_B, which coincide in contact).
  OutPortA.F + OutPortB.F = zeros(3);
  OutPortA.M + OutPortB.M = zeros(3);
end Constraint;
