within UnilateralMBS.Constraints;
partial model SurfacesOfConstraintCausalDifferential "Closest points of two regular surfaces from the differential form of (2.1), on the causal constraint (added; copy of SurfacesOfConstraintAcausalDifferential)"
  // added (not in the paper): SurfacesOfConstraintAcausalDifferential with the base class
  // UnilateralConstraintCausalAddOnRegular instead of UnilateralConstraintAcausalAddOnRegular;
  // the equations are unchanged. Its comments follow.
  // reconstructed: the paper names this class but does not print it. It does not depend on
  // the shapes: a derived class supplies, at the current points, the values gA, gB, the
  // gradients gradgA, gradgB (2.2) and the Hessians HA, HB of g_A, g_B (all in AF), plus
  // initial equations for rPA, rPB, lambda, mu.
  //
  // Problem 2 of the paper: the system (2.1)
  //   grad g_A(r_PA) + lambda*grad g_B(r_PB) = 0,  r_PA - r_PB - mu*grad g_B(r_PB) = 0,
  //   g_A(r_PA) = 0,  g_B(r_PB) = 0
  // is integrated in differential form. With g(r) = f(T'*(r - r_O)) one has
  //   d/dt grad g(r_P) = omega x grad g + H*(d r_P/dt - v_P),
  //   d/dt g(r_P)      = grad g . (d r_P/dt - v_P),
  // where v_P (= vrA, vrB) is the velocity of the material point at P and omega the body's
  // angular velocity in AF. The same 8 equations hold in every constraint state; in contact
  // mu stays 0 because v_rn is driven to 0 by UnilateralConstraintAcausalAddOnRegular.
  extends UnilateralConstraintCausalAddOnRegular;
  Real gA "g_A at P_A (0 up to drift of the integration)";
  Real gB "g_B at P_B (0 up to drift of the integration)";
  Real HA[3, 3] "Hessian of g_A at P_A, AF";
  Real HB[3, 3] "Hessian of g_B at P_B, AF";
  SI.Velocity DrPA[3] "d rPA/dt (physical time)";
  SI.Velocity DrPB[3] "d rPB/dt (physical time)";
  Real Dlambda "d lambda/dt (physical time)";
  Real Dmu "d mu/dt (physical time)";
equation
  // time scaling as for the bodies: der() is with respect to the regularising variable
  der(rPA) = Active*DrPA;
  der(rPB) = Active*DrPB;
  der(lambda) = Active*Dlambda;
  der(mu) = Active*Dmu;
  // time derivative of (2.1)
  cross(InPortA.omega, gradgA) + HA*(DrPA - vrA) + Dlambda*gradgB
    + lambda*(cross(InPortB.omega, gradgB) + HB*(DrPB - vrB)) = zeros(3);
  DrPA - DrPB - Dmu*gradgB - mu*(cross(InPortB.omega, gradgB) + HB*(DrPB - vrB)) = zeros(3);
  gradgA*(DrPA - vrA) = 0;
  gradgB*(DrPB - vrB) = 0;
end SurfacesOfConstraintCausalDifferential;
