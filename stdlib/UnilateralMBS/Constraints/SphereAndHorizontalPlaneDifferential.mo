within UnilateralMBS.Constraints;
model SphereAndHorizontalPlaneDifferential "Unilateral constraint between a horizontal plane (body A) and a sphere (body B), closest points from the differential form (added; not in the paper)"
  // added (not in the paper): the plane/sphere pair, written like
  // EllipsoidAndHorizontalPlaneDifferential.
  // A: plane f_A(rho) = rho[2] (the plane y = 0 of A's body frame, outer normal +y).
  // B: sphere f_B(rho) = (rho*rho)/R^2 - 1 about B's centre of mass. It is invariant under
  //    rotation, so g_B(r) = |r - r_OB|^2/R^2 - 1 in AF: T_B is not needed.
  extends SurfacesOfConstraintAcausalDifferential;
  parameter SI.Length R = 1 "Radius of the sphere B";
  Real rhoA[3] "P_A in the body frame of A";
  Real dB[3] "P_B - r_OB, AF";
  // reference: closed form of the closest points (P_B = r_OB - R*nA)
  Real nA[3] "Unit normal of the plane, AF";
  SI.Position rPBExact[3] "Closed-form closest point of B";
  SI.Length gap "Signed distance (rPB - rPA).normA from the integrated points";
  SI.Length gapExact "Closed-form signed distance between plane and sphere";
  SI.Length rPBDrift "|rPB - rPBExact|: drift of the differential form";
equation
  // plane A
  rhoA = transpose(InPortA.T)*(rPA - InPortA.r);
  gA = rhoA[2];
  gradgA = InPortA.T*{0, 1, 0};
  HA = zeros(3, 3);
  // sphere B
  dB = rPB - InPortB.r;
  gB = (dB*dB)/R^2 - 1;
  gradgB = (2/R^2)*dB;
  HB = (2/R^2)*identity(3);
  // closed-form reference
  nA = InPortA.T*{0, 1, 0};
  rPBExact = InPortB.r - R*nA;
  gapExact = (InPortB.r - InPortA.r)*nA - R;
  gap = (rPB - rPA)*normA;
  rPBDrift = sqrt((rPB - rPBExact)*(rPB - rPBExact));
initial equation
  // consistent start from the closed form: P_B is the lowest point of the sphere, P_A its
  // projection on the plane, then mu and lambda from (2.1)
  rPB = rPBExact;
  rPA = rPB - ((rPB - InPortA.r)*nA)*nA;
  mu*(gradgB*gradgB) = (rPA - rPB)*gradgB;
  lambda*(gradgB*gradgB) = -(gradgA*gradgB);
  // Drawn by `unimo animate` (docs/animation.md): the plane y = 0 of body A.
  annotation(__unimo_visual(shape = "plane", normal = {0, 1, 0}, position = InPortA.r, rotation = InPortA.T));
end SphereAndHorizontalPlaneDifferential;
