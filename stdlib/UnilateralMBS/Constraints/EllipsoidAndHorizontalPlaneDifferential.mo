within UnilateralMBS.Constraints;
model EllipsoidAndHorizontalPlaneDifferential "Unilateral constraint between a horizontal plane (body A) and an ellipsoid (body B) (not printed in the paper; reconstructed from spec A.3)"
  // reconstructed: the paper names this class but does not print it.
  // A: plane f_A(rho) = rho[2] (the plane y = 0 of A's body frame, outer normal +y).
  // B: ellipsoid f_B(rho) = (rho[1]/a)^2 + (rho[2]/b)^2 + (rho[3]/c)^2 - 1 in B's principal axes.
  extends SurfacesOfConstraintAcausalDifferential;
  parameter SI.Length a = 1 "Semi-axis of the ellipsoid along body x of B";
  parameter SI.Length b = 1 "Semi-axis of the ellipsoid along body y of B";
  parameter SI.Length c = 1 "Semi-axis of the ellipsoid along body z of B";
  Real rhoA[3] "P_A in the body frame of A";
  Real rhoB[3] "P_B in the body frame of B";
  // reference (spec A.3): closed form of the closest point of B, used to measure the drift
  // of the integrated differential form
  Real nA[3] "Unit normal of the plane, AF";
  Real ABsqn[3] "T_B*diag(a^2, b^2, c^2)*T_B'*nA";
  SI.Position rPBExact[3] "Closed-form closest point of B";
  SI.Length gap "Signed distance (rPB - rPA).normA from the integrated points";
  SI.Length gapExact "Closed-form signed distance between plane and ellipsoid";
  SI.Length rPBDrift "|rPB - rPBExact|: drift of the differential form";
equation
  // plane A
  rhoA = transpose(InPortA.T)*(rPA - InPortA.r);
  gA = rhoA[2];
  gradgA = InPortA.T*{0, 1, 0};
  HA = zeros(3, 3);
  // ellipsoid B
  rhoB = transpose(InPortB.T)*(rPB - InPortB.r);
  gB = (rhoB[1]/a)^2 + (rhoB[2]/b)^2 + (rhoB[3]/c)^2 - 1;
  gradgB = InPortB.T*{2*rhoB[1]/a^2, 2*rhoB[2]/b^2, 2*rhoB[3]/c^2};
  HB = InPortB.T*diagonal({2/a^2, 2/b^2, 2/c^2})*transpose(InPortB.T);
  // closed-form reference
  nA = InPortA.T*{0, 1, 0};
  ABsqn = InPortB.T*diagonal({a^2, b^2, c^2})*transpose(InPortB.T)*nA;
  rPBExact = InPortB.r - ABsqn/sqrt(nA*ABsqn);
  gapExact = (InPortB.r - InPortA.r)*nA - sqrt(nA*ABsqn);
  gap = (rPB - rPA)*normA;
  rPBDrift = sqrt((rPB - rPBExact)*(rPB - rPBExact));
initial equation
  // consistent start of the integrated points from the closed form: P_B is the point of B
  // whose outer normal is -nA, P_A its projection on the plane, then mu and lambda from (2.1)
  rPB = rPBExact;
  rPA = rPB - ((rPB - InPortA.r)*nA)*nA;
  mu*(gradgB*gradgB) = (rPA - rPB)*gradgB;
  lambda*(gradgB*gradgB) = -(gradgA*gradgB);
  // Drawn by `unimo animate` (docs/animation.md): the plane y = 0 of body A.
  annotation(__unimo_visual(shape = "plane", normal = {0, 1, 0}, position = InPortA.r, rotation = InPortA.T));
end EllipsoidAndHorizontalPlaneDifferential;
