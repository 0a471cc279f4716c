model MBSAcausalDifferential "Heavy ellipsoid flying, sliding and rolling on a horizontal plane: acausal unilateral constraint with regularised time (paper A, section 4, example 1)"
  import SI = Modelica.SIunits;
  // The paper writes `Period` and `Time` unqualified; they are Modelica.SIunits types.
  parameter SI.Period TimeScale = 1;
  // fixed=true added on deltat and t so that the initial value problem is complete
  SI.Period deltat(start=1, fixed=true) "dt/dtau (times TimeScale)";
  SI.Time t(start=0, fixed=true) "Physical time; the Modelica time is the regularising variable tau";

  // Parameters of example 1 (spec A.9; the paper does not print them): all (chosen) there.
  parameter SI.Length a = 1.0 "Ellipsoid semi-axis along body x";
  parameter SI.Length b = 0.8 "Ellipsoid semi-axis along body y";
  parameter SI.Length c = 1.2 "Ellipsoid semi-axis along body z";
  parameter SI.Mass m = 1 "Mass of the ellipsoid";
  parameter SI.Acceleration g = 1 "Gravity acceleration (along -y)";
  parameter Real k = 0.6 "Coefficient of restitution";
  parameter Real f = 0.08 "Coefficient of Coulomb friction";
  parameter SI.Velocity delta = 1e-3 "Regularising parameter of dry friction";
  parameter SI.Length ClearanceTolerance = 1e-12 "Jump height below which the body lands";
  parameter SI.DampingCoefficient ConstraintAttraction = 1 "Pull of v_rn back to 0 in contact";

  // Components of Figure 4.1 (their classes are not printed in the paper).
  UnilateralMBS.Bodies.FixedBaseBody HorizontalSurface "Base body: the horizontal plane y = 0 fixed in AF";
  UnilateralMBS.Bodies.HeavyEllipsoidBody FlySlideRollBody(
    semiA=a, semiB=b, semiC=c, m=m, g=g,
    r(start={0, 5, 0}),
    v(start={0.05, 0, 0}),
    q(start={1, 0, 0, 0}),
    omega(start={0, -10, 2})) "Heavy homogeneous ellipsoid, initial data (4.8)";
  UnilateralMBS.Constraints.EllipsoidAndHorizontalPlaneDifferential ConstraintSurfaces(
    a=a, b=b, c=c, k=k, f=f, delta=delta,
    ClearanceTolerance=ClearanceTolerance,
    ConstraintAttraction=ConstraintAttraction) "Unilateral constraint: A = plane, B = ellipsoid";
equation
  // reconstructed: the connections are drawn in Figure 4.1, not printed as code
  connect(HorizontalSurface.OutPort, ConstraintSurfaces.InPortA);
  connect(ConstraintSurfaces.OutPortA, HorizontalSurface.InPort1);
  connect(FlySlideRollBody.OutPort, ConstraintSurfaces.InPortB);
  connect(ConstraintSurfaces.OutPortB, FlySlideRollBody.InPort1);
  connect(ConstraintSurfaces.OutImpactSignalB, FlySlideRollBody.InImpactSignal1);

  der(deltat) = 0;
  // The OCR reads "deltatTimeScale"; deltat/TimeScale is the dimensionless choice
  // (Period/Period). The reinit values below equal deltat only for TimeScale = 1.
  der(t) = deltat/TimeScale;
  // The paper writes two when-equations that reinit the same variables; Modelica 3 needs
  // them in one when-equation, so the second becomes an elsewhen branch (Impact requires
  // State = 0, the landing means State > 0: both never hold in the same solution).
  when ConstraintSurfaces.Impact then
    reinit(deltat, min(1, 2*abs(ConstraintSurfaces.relvn/ConstraintSurfaces.relan)));
    reinit(FlySlideRollBody.Active, min(1, 2*abs(ConstraintSurfaces.relvn/ConstraintSurfaces.relan)));
    reinit(ConstraintSurfaces.Active, min(1, 2*abs(ConstraintSurfaces.relvn/ConstraintSurfaces.relan)));
  elsewhen ConstraintSurfaces.StateIndicator > 0.5 then
    reinit(deltat, 1);
    reinit(FlySlideRollBody.Active, 1);
    reinit(ConstraintSurfaces.Active, 1);
  elsewhen ConstraintSurfaces.Launching then
    // added (not in the paper): in Flight with the bodies accelerating apart the
    // predicted time to the next impact no longer holds; back to the physical time scale
    reinit(deltat, 1);
    reinit(FlySlideRollBody.Active, 1);
    reinit(ConstraintSurfaces.Active, 1);
  end when;
  annotation (experiment(StartTime=0, StopTime=150, Tolerance=1e-8));
end MBSAcausalDifferential;
