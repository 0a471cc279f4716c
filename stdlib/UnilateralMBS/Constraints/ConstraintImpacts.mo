within UnilateralMBS.Constraints;
partial model ConstraintImpacts "Base model of a constraint that transmits impacts"
  extends Constraint(
    redeclare input Interfaces.KinematicPortImpacts InPortA,
    redeclare output Interfaces.WrenchPortImpacts OutPortA,
    redeclare input Interfaces.KinematicPortImpacts InPortB,
    redeclare output Interfaces.WrenchPortImpacts OutPortB);
equation
  OutPortA.ImpactForce + OutPortB.ImpactForce = zeros(3);
  OutPortA.ImpactTorque + OutPortB.ImpactTorque = zeros(3);
end ConstraintImpacts;
