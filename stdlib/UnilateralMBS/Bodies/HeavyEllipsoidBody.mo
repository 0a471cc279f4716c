within UnilateralMBS.Bodies;
model HeavyEllipsoidBody "Homogeneous heavy ellipsoid processing impacts (not printed in the paper; reconstructed from spec A.2, A.9)"
  // reconstructed: the paper's example instantiates FlySlideRollBody without printing its
  // class. Homogeneous ellipsoid with semi-axes a, b, c along the body axes; gravity g
  // along -y of AF is the only external force.
  extends RigidBodyImpactsAcausal(I=m/5*diagonal({b^2 + c^2, a^2 + c^2, a^2 + b^2}));
  parameter SI.Length a = 1 "Semi-axis along body x";
  parameter SI.Length b = 1 "Semi-axis along body y";
  parameter SI.Length c = 1 "Semi-axis along body z";
  parameter SI.Acceleration g = 9.81 "Gravity acceleration (acts along -y of AF)";
equation
  F1 = {0, -m*g, 0};
  M1 = zeros(3);
  ImpactForce1 = zeros(3);
  ImpactTorque1 = zeros(3);
end HeavyEllipsoidBody;
