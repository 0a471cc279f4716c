within UnilateralMBS.Constraints;
model SphereAndSphereDifferential "Unilateral constraint between two spheres A and B (both may move), closest points from the differential form (added; not in the paper)"
  // added (not in the paper): sphere/sphere pair, written like
  // EllipsoidAndHorizontalPlaneDifferential.
  // A: sphere f_A(rho) = (rho*rho)/RA^2 - 1, B: sphere f_B(rho) = (rho*rho)/RB^2 - 1, each
  // about its body's centre of mass. Both are rotation invariant, so in AF
  // g(r) = |r - r_O|^2/R^2 - 1, grad g = 2*(r - r_O)/R^2, H = 2/R^2*identity(3).
  extends SurfacesOfConstraintAcausalDifferential;
  parameter SI.Length RA = 1 "Radius of the sphere A";
  parameter SI.Length RB = 1 "Radius of the sphere B";
  Real dA[3] "P_A - r_OA, AF";
  Real dB[3] "P_B - r_OB, AF";
  // reference: closed form of the closest points on the line of centres
  SI.Length centreDistance "|r_OB - r_OA|";
  Real nAB[3] "Unit vector from the centre of A to the centre of B, AF";
  SI.Position rPAExact[3] "Closed-form closest point of A";
  SI.Position rPBExact[3] "Closed-form closest point of B";
  SI.Length gap "Signed distance (rPB - rPA).normA from the integrated points";
  SI.Length gapExact "Closed-form signed distance |r_OB - r_OA| - RA - RB";
  SI.Length rPADrift "|rPA - rPAExact|: drift of the differential form";
  SI.Length rPBDrift "|rPB - rPBExact|: drift of the differential form";
equation
  // sphere A
  dA = rPA - InPortA.r;
  gA = (dA*dA)/RA^2 - 1;
  gradgA = (2/RA^2)*dA;
  HA = (2/RA^2)*identity(3);
  // sphere B
  dB = rPB - InPortB.r;
  gB = (dB*dB)/RB^2 - 1;
  gradgB = (2/RB^2)*dB;
  HB = (2/RB^2)*identity(3);
  // closed-form reference
  centreDistance = sqrt((InPortB.r - InPortA.r)*(InPortB.r - InPortA.r));
  nAB = (InPortB.r - InPortA.r)/centreDistance;
  rPAExact = InPortA.r + RA*nAB;
  rPBExact = InPortB.r - RB*nAB;
  gapExact = centreDistance - RA - RB;
  gap = (rPB - rPA)*normA;
  rPADrift = sqrt((rPA - rPAExact)*(rPA - rPAExact));
  rPBDrift = sqrt((rPB - rPBExact)*(rPB - rPBExact));
initial equation
  // consistent start from the closed form, then mu and lambda from (2.1)
  // (mu = gapExact*RB/2, lambda = RB/RA)
  rPA = rPAExact;
  rPB = rPBExact;
  mu*(gradgB*gradgB) = (rPA - rPB)*gradgB;
  lambda*(gradgB*gradgB) = -(gradgA*gradgB);
end SphereAndSphereDifferential;
