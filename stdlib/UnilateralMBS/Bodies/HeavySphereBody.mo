within UnilateralMBS.Bodies;
model HeavySphereBody "Homogeneous heavy sphere with one wrench port, processing impacts (added; not in the paper)"
  // added (not in the paper): like HeavyEllipsoidBody with a = b = c = R, inertia 2/5*m*R^2.
  // Gravity g along -y of AF is the only external force.
  extends RigidBodyImpactsAcausal(I=2/5*m*R^2*identity(3));
  parameter SI.Length R = 1 "Radius";
  parameter SI.Acceleration g = 9.81 "Gravity acceleration (acts along -y of AF)";
equation
  F1 = {0, -m*g, 0};
  M1 = zeros(3);
  ImpactForce1 = zeros(3);
  ImpactTorque1 = zeros(3);
  // Drawn by `unimo animate` (docs/animation.md).
  annotation(__unimo_visual(shape = "sphere", size = {R}, position = r, rotation = T));
end HeavySphereBody;
