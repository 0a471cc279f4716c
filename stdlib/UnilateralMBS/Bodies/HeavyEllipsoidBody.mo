within UnilateralMBS.Bodies;
model HeavyEllipsoidBody "Homogeneous heavy ellipsoid processing impacts (not printed in the paper; reconstructed from spec A.2, A.9)"
  // reconstructed: the paper's example instantiates FlySlideRollBody without printing its
  // class. Homogeneous ellipsoid with semi-axes semiA, semiB, semiC along the body axes (not
  // a, b, c: RigidBody already has the acceleration a); gravity g
  // along -y of AF is the only external force.
  extends RigidBodyImpactsAcausal(I=m/5*diagonal({semiB^2 + semiC^2, semiA^2 + semiC^2, semiA^2 + semiB^2}));
  parameter SI.Length semiA = 1 "Semi-axis along body x";
  parameter SI.Length semiB = 1 "Semi-axis along body y";
  parameter SI.Length semiC = 1 "Semi-axis along body z";
  parameter SI.Acceleration g = 9.81 "Gravity acceleration (acts along -y of AF)";
equation
  F1 = {0, -m*g, 0};
  M1 = zeros(3);
  ImpactForce1 = zeros(3);
  ImpactTorque1 = zeros(3);
  // Drawn by `unimo animate` (docs/animation.md).
  annotation(__unimo_visual(shape = "ellipsoid", size = {semiA, semiB, semiC}, position = r, rotation = T));
end HeavyEllipsoidBody;
