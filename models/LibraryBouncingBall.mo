model LibraryBouncingBall "Sphere dropped on a horizontal plane, built from the UnilateralMBS library: frictionless bounces with restitution, Zeno landing by time regularisation, then rest"
  import SI = Modelica.SIunits;
  // The Modelica `time` is the regularising variable tau; physical time is t (der(t) = deltat).
  parameter SI.Period TimeScale = 1;
  SI.Period deltat(start=1, fixed=true) "dt/dtau (times TimeScale)";
  SI.Time t(start=0, fixed=true) "Physical time";

  parameter SI.Length R = 0.1 "Radius of the ball";
  parameter SI.Length h0 = 1 "Initial height of the lowest point of the ball above the plane";
  parameter SI.Mass m = 1 "Mass of the ball";
  parameter SI.Acceleration g = 9.81 "Gravity acceleration (along -y)";
  parameter Real k = 0.8 "Coefficient of restitution";
  parameter Real f = 0 "Coefficient of Coulomb friction (no spin, vertical drop: no tangent motion)";
  parameter SI.Velocity delta = 1e-3 "Regularising parameter of dry friction";
  parameter SI.Length ClearanceTolerance = 1e-12 "Predicted jump height below which the ball lands";
  parameter SI.DampingCoefficient ConstraintAttraction = 1 "Pull of v_rn back to 0 in contact";
  parameter SI.Time tStop = 6 "Physical stop time (the Zeno time is sqrt(2*h0/g)*(1 + k)/(1 - k) = 4.064 s)";
  parameter SI.Time tZeno = sqrt(2*h0/g)*(1 + k)/(1 - k) "Closed-form accumulation time of the impacts";

  UnilateralMBS.Bodies.FixedBaseBody Table "The plane y = 0";
  UnilateralMBS.Bodies.HeavySphereBody Ball(
    R=R, m=m, g=g,
    r(start={0, h0 + R, 0}),
    v(start={0, 0, 0}),
    q(start={1, 0, 0, 0}),
    omega(start={0, 0, 0})) "Homogeneous heavy ball, dropped without spin";
  UnilateralMBS.Constraints.SphereAndHorizontalPlaneDifferential Contact(
    R=R, k=k, f=f, delta=delta,
    ClearanceTolerance=ClearanceTolerance,
    ConstraintAttraction=ConstraintAttraction) "Unilateral constraint: A = plane, B = ball";
  Integer impacts(start=0, fixed=true) "Number of impacts so far";
equation
  connect(Table.OutPort, Contact.InPortA);
  connect(Contact.OutPortA, Table.InPort1);
  connect(Ball.OutPort, Contact.InPortB);
  connect(Contact.OutPortB, Ball.InPort1);
  connect(Contact.OutImpactSignalB, Ball.InImpactSignal1);

  der(deltat) = 0;
  der(t) = deltat/TimeScale;
  // time regularisation as in MBSAcausalDifferential, plus the reset on a launch
  when Contact.Impact then
    reinit(deltat, min(1, 2*abs(Contact.relvn/Contact.relan)));
    reinit(Ball.Active, min(1, 2*abs(Contact.relvn/Contact.relan)));
    reinit(Contact.Active, min(1, 2*abs(Contact.relvn/Contact.relan)));
  elsewhen Contact.StateIndicator > 0.5 then
    reinit(deltat, 1);
    reinit(Ball.Active, 1);
    reinit(Contact.Active, 1);
  elsewhen Contact.Launching then
    reinit(deltat, 1);
    reinit(Ball.Active, 1);
    reinit(Contact.Active, 1);
  end when;
  when Contact.Impact then
    impacts = pre(impacts) + 1;
  end when;
  when t >= tStop then
    terminate("physical stop time reached");
  end when;
  annotation (experiment(StartTime=0, StopTime=1000, Tolerance=1e-8));
end LibraryBouncingBall;
