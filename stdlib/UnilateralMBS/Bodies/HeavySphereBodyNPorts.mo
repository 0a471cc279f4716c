within UnilateralMBS.Bodies;
model HeavySphereBodyNPorts "Homogeneous heavy sphere with nPorts constraint ports, processing impacts (added; not in the paper)"
  // added (not in the paper): HeavySphereBody for a sphere touched by several constraints
  // (e.g. the table and the other balls), see RigidBodyImpactsAcausalNPorts.
  extends RigidBodyImpactsAcausalNPorts(I=2/5*m*R^2*identity(3));
  parameter SI.Length R = 1 "Radius";
  parameter SI.Acceleration g = 9.81 "Gravity acceleration (acts along -y of AF)";
equation
  F1 = {0, -m*g, 0};
  M1 = zeros(3);
  ImpactForce1 = zeros(3);
  ImpactTorque1 = zeros(3);
  // Drawn by `unimo animate` (docs/animation.md).
  annotation(__unimo_visual(shape = "sphere", size = {R}, position = r, rotation = T));
end HeavySphereBodyNPorts;
