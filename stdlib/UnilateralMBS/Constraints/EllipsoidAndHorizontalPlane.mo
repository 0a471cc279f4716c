within UnilateralMBS.Constraints;
model EllipsoidAndHorizontalPlane "Unilateral constraint between a horizontal plane (body A) and an ellipsoid (body B), closest points in closed form (added, not in the paper)"
  // added (not in the paper; change S10 of docs/paper-a-transcription.md): the closest
  // points are computed from the positions and attitudes by the closed form of spec A.3
  // instead of integrating the differential form of (2.1) as the paper advises
  // (EllipsoidAndHorizontalPlaneDifferential, kept for the record). Integrated points
  // drift from the surfaces (up to 5.7e-6 over FlySlideRoll's 150 s) and a landing
  // decided on a drifting gap lands early; here rPB lies on the ellipsoid and rPA on the
  // plane up to rounding, and the gap is the true signed distance of the two surfaces.
  // A: plane f_A(rho) = rho[2] (the plane y = 0 of A's body frame, outer normal +y).
  // B: ellipsoid (rho[1]/a)^2 + (rho[2]/b)^2 + (rho[3]/c)^2 = 1 in B's principal axes;
  // P_B is its point whose outer normal is -nA (its support point in direction -nA).
  extends UnilateralConstraintAcausalAddOnRegular;
  parameter SI.Length a = 1 "Semi-axis of the ellipsoid along body x of B";
  parameter SI.Length b = 1 "Semi-axis of the ellipsoid along body y of B";
  parameter SI.Length c = 1 "Semi-axis of the ellipsoid along body z of B";
  Real nA[3] "Unit outer normal of the plane, AF";
  Real ABsqn[3] "T_B*diag(a^2, b^2, c^2)*T_B'*nA";
  SI.Length support "sqrt(nA*ABsqn): distance from B's centre to its tangent plane parallel to A";
  SI.Length gap "Signed distance (rPB - rPA).normA (> 0 apart)";
equation
  nA = InPortA.T*{0, 1, 0};
  ABsqn = InPortB.T*diagonal({a^2, b^2, c^2})*transpose(InPortB.T)*nA;
  support = sqrt(nA*ABsqn);
  rPB = InPortB.r - ABsqn/support;
  rPA = rPB - ((rPB - InPortA.r)*nA)*nA;
  // gradients (2.2): grad g_A = nA; grad g_B at P_B = T_B*2*diag(1/a^2, ...)*rho_B
  // = -2*nA/support, since rho_B = -diag(a^2, ...)*T_B'*nA/support
  gradgA = nA;
  gradgB = -2*nA/support;
  // multipliers of (2.1): rPA - rPB = mu*gradgB, gradgA = -lambda*gradgB
  gap = (rPB - rPA)*nA;
  mu = gap*support/2;
  lambda = support/2;
  // added (not in the paper; S13): in contact the gap is an invariant, held by the
  // simulator's projection after each step and event (docs/backend.md), not only by the
  // Baumgarte term of UnilateralConstraintAcausalAddOnRegular, which leaves the
  // integration error (1.6e-9 with Radau5 at rtol 1e-8); with it |Gap| in contact stays
  // at rounding whatever the tolerance. Declared here, where the closest points are the
  // closed form, and not for the integrated points of the differential classes, whose
  // gap is no function of the bodies' positions alone.
  if StateIndicator > 0.5 then
    Unimo.invariant(Gap);
  end if;
  // Drawn by `unimo animate` (docs/animation.md): the plane y = 0 of body A.
  annotation(__unimo_visual(shape = "plane", normal = {0, 1, 0}, position = InPortA.r, rotation = InPortA.T));
end EllipsoidAndHorizontalPlane;
