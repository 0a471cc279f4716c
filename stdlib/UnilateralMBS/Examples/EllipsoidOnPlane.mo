within UnilateralMBS.Examples;
model EllipsoidOnPlane "Heavy ellipsoid on a fixed horizontal plane with one acausal unilateral constraint and time regularisation (paper A, section 4)"
  // The container of MBSAcausalDifferential (Figure 4.1) with its data as parameters, so
  // that FlySlideRoll, SlideRollSwitch and MarkeevEllipsoid differ only in modifiers.
  // The Modelica `time` is the regularising variable tau; `t` is physical time.
  parameter SI.Period TimeScale = 1;
  parameter SI.Length a = 1.0 "Ellipsoid semi-axis along body x";
  parameter SI.Length b = 0.8 "Ellipsoid semi-axis along body y";
  parameter SI.Length c = 1.2 "Ellipsoid semi-axis along body z";
  parameter SI.Mass m = 1 "Mass of the ellipsoid";
  parameter SI.Acceleration g = 1 "Gravity acceleration (along -y)";
  parameter Real k = 0.6 "Coefficient of restitution";
  parameter Real f = 0.08 "Coefficient of Coulomb friction";
  parameter SI.Velocity delta = 1e-3 "Regularising parameter of dry friction";
  parameter SI.Length ClearanceTolerance = 1e-10 "Jump height below which the body lands";
  parameter SI.DampingCoefficient ConstraintAttraction = 1 "Pull of v_rn back to 0 in contact";
  parameter SI.Position r0[3] = {0, 5, 0} "Initial centre of mass";
  parameter SI.Velocity v0[3] = {0.05, 0, 0} "Initial velocity";
  parameter Real q0[4] = {1, 0, 0, 0} "Initial attitude";
  parameter SI.AngularVelocity omega0[3] = {0, -10, 2} "Initial angular velocity, body frame";
  parameter SI.Time tStop = 150 "Physical time at which the simulation ends";
  parameter SI.Length Clearance0 = 1 "Initial predicted jump height: 0 starts a body that touches the plane in contact, 1 in Flight";

  SI.Period deltat(start=1, fixed=true) "dt/dtau (times TimeScale)";
  SI.Time t(start=0, fixed=true) "Physical time";

  Bodies.FixedBaseBody HorizontalSurface "The plane y = 0 fixed in AF";
  Bodies.HeavyEllipsoidBody FlySlideRollBody(
    semiA=a, semiB=b, semiC=c, m=m, g=g,
    r(start=r0), v(start=v0), q(start=q0), omega(start=omega0)) "Heavy homogeneous ellipsoid";
  Constraints.EllipsoidAndHorizontalPlane ConstraintSurfaces(
    a=a, b=b, c=c, k=k, f=f, delta=delta,
    ClearanceTolerance=ClearanceTolerance,
    ConstraintAttraction=ConstraintAttraction,
    Clearance(start=Clearance0)) "Unilateral constraint: A = plane, B = ellipsoid";

  // Figures reported in docs/results/paper-a.md
  SI.Energy Energy "Kinetic plus potential energy of the ellipsoid";
  SI.Length CentreHeight = FlySlideRollBody.r[2] "Height of the centre of mass";
  SI.AngularVelocity OmegaAF[3] = FlySlideRollBody.T*FlySlideRollBody.omega "Angular velocity, AF";
  Integer Impacts(start=0, fixed=true) "Impacts so far";
  Integer Switches(start=0, fixed=true) "Changes of the constraint state so far";
  discrete SI.Time tFirstRolling(start=-1, fixed=true) "Physical time of the first transfer to Rolling (-1: not yet)";
  discrete SI.Time tFirstContact(start=-1, fixed=true) "Physical time of the first landing or of the start in contact (-1: not yet)";
equation
  connect(HorizontalSurface.OutPort, ConstraintSurfaces.InPortA);
  connect(ConstraintSurfaces.OutPortA, HorizontalSurface.InPort1);
  connect(FlySlideRollBody.OutPort, ConstraintSurfaces.InPortB);
  connect(ConstraintSurfaces.OutPortB, FlySlideRollBody.InPort1);
  connect(ConstraintSurfaces.OutImpactSignalB, FlySlideRollBody.InImpactSignal1);

  der(deltat) = 0;
  der(t) = deltat/TimeScale;
  // Time regularisation (spec A.7): at an impact every Active and deltat shrink to the
  // predicted time to the next impact; on landing, and when the bodies accelerate apart
  // in Flight (the prediction no longer holds), they return to 1.
  when ConstraintSurfaces.Impact then
    reinit(deltat, min(1, 2*abs(ConstraintSurfaces.relvn/ConstraintSurfaces.relan)));
    reinit(FlySlideRollBody.Active, min(1, 2*abs(ConstraintSurfaces.relvn/ConstraintSurfaces.relan)));
    reinit(ConstraintSurfaces.Active, min(1, 2*abs(ConstraintSurfaces.relvn/ConstraintSurfaces.relan)));
  elsewhen ConstraintSurfaces.StateIndicator > 0.5 then
    reinit(deltat, 1);
    reinit(FlySlideRollBody.Active, 1);
    reinit(ConstraintSurfaces.Active, 1);
  elsewhen ConstraintSurfaces.Launching then
    reinit(deltat, 1);
    reinit(FlySlideRollBody.Active, 1);
    reinit(ConstraintSurfaces.Active, 1);
  end when;

  Energy = 0.5*m*(FlySlideRollBody.v*FlySlideRollBody.v)
    + 0.5*FlySlideRollBody.omega*(FlySlideRollBody.I*FlySlideRollBody.omega)
    + m*g*FlySlideRollBody.r[2];
  when ConstraintSurfaces.Impact then
    Impacts = pre(Impacts) + 1;
  end when;
  when change(ConstraintSurfaces.State) then
    Switches = pre(Switches) + 1;
  end when;
  when ConstraintSurfaces.State > 0 and pre(tFirstContact) < 0 then
    tFirstContact = t;
  end when;
  when ConstraintSurfaces.State == 2 and pre(tFirstRolling) < 0 then
    tFirstRolling = t;
  end when;
  // A Zeno sequence whose bounces fall below what the integration resolves before the
  // predicted jump height drops under ClearanceTolerance never lands: the time scale
  // shrinks until physical time stops. Say so instead of running on.
  assert(deltat > 1e-14, "the time regularisation collapsed (deltat <= 1e-14): the bounces are below the integration accuracy before they land; raise ClearanceTolerance or tighten the tolerance");
  when t >= tStop then
    terminate("physical time reached tStop");
  end when;
end EllipsoidOnPlane;
