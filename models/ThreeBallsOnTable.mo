model ThreeBallsOnTable "Three balls on a table (paper A, section 1: n = 3 balls, n(n+1)/2 = 6 unilateral constraints, one acausal object each; no hand-enumerated system states)"
  import SI = Modelica.SIunits;
  // The Modelica `time` is the regularising variable tau; physical time is t (der(t) = deltat).
  parameter SI.Period TimeScale = 1;
  SI.Period deltat(start=1, fixed=true) "dt/dtau (times TimeScale)";
  SI.Time t(start=0, fixed=true) "Physical time";

  // Parameters (all chosen, not from the paper)
  parameter Integer n = 3 "Number of balls";
  parameter SI.Length R = 0.1 "Radius of every ball";
  parameter SI.Mass m = 1 "Mass of every ball";
  parameter SI.Acceleration g = 9.81 "Gravity acceleration (along -y)";
  parameter SI.Length h1 = 0.05 "Initial drop height of ball 1 (lowest point above the table)";
  parameter SI.Velocity v0 = 1 "Initial velocity of ball 1 along +x (no spin)";
  parameter SI.Position x2 = 1.2 "Initial x of ball 2 (ball 1 starts at x = 0; it lands before reaching ball 2)";
  parameter SI.Length spacing = 0.3 "Distance between the centres of balls 2 and 3 at t = 0";
  parameter Real kTable = 0.8 "Coefficient of restitution ball-table";
  parameter Real fTable = 0.1 "Coefficient of Coulomb friction ball-table";
  parameter Real kBalls = 0.8 "Coefficient of restitution ball-ball";
  // A frictional ball-ball impact of rolling balls has a vertical tangent impulse: it would
  // push a ball into the table while that ball-table constraint is in contact, an indirect
  // impact the library does not process (paper A: "under further development"). So the
  // ball-ball contacts are frictionless.
  parameter Real fBalls = 0 "Coefficient of Coulomb friction ball-ball";
  parameter SI.Velocity delta = 1e-3 "Regularising parameter of dry friction";
  parameter SI.Length ClearanceTolerance = 1e-12 "Predicted jump height below which a contact lands";
  parameter SI.DampingCoefficient ConstraintAttraction = 1 "Pull of v_rn back to 0 in contact";
  parameter SI.Time tStop = 4 "Physical stop time";

  UnilateralMBS.Bodies.FixedBaseBodyNPorts Table(nPorts=n) "The table: the plane y = 0";
  // port 1: table; ports 2, 3: the two other balls (see the connections)
  UnilateralMBS.Bodies.HeavySphereBodyNPorts Ball[n](
    each nPorts=n, each R=R, each m=m, each g=g,
    r(start={{0, R + h1, 0}, {x2, R, 0}, {x2 + spacing, R, 0}}),
    v(start={{v0, 0, 0}, {0, 0, 0}, {0, 0, 0}}),
    each q(start={1, 0, 0, 0}),
    each omega(start={0, 0, 0})) "Homogeneous heavy balls: ball 1 dropped and thrown along +x, balls 2 and 3 at rest on the table";
  // Balls 2 and 3 start exactly on the table: Clearance(start=0) makes their constraints
  // land at once (Rolling) instead of starting in Flight; ball 1 starts in Flight.
  UnilateralMBS.Constraints.SphereAndHorizontalPlaneDifferential TableContact[n](
    each R=R, each k=kTable, each f=fTable, each delta=delta,
    each ClearanceTolerance=ClearanceTolerance,
    each ConstraintAttraction=ConstraintAttraction,
    Clearance(start={1, 0, 0}),
    StateIndicator(start={0, 2, 2})) "Ball i (B) on the table (A)";
  // BallContact[1]: balls 1 (A) and 2 (B); [2]: balls 1 (A) and 3 (B); [3]: balls 2 (A) and 3 (B)
  UnilateralMBS.Constraints.SphereAndSphereDifferential BallContact[3](
    each RA=R, each RB=R, each k=kBalls, each f=fBalls, each delta=delta,
    each ClearanceTolerance=ClearanceTolerance,
    each ConstraintAttraction=ConstraintAttraction) "Ball-ball constraints";
  Real newScale "At an impact: min over the impacting ball-table constraints of min(1, 2|v_rn/a_rn|), else the current scale";
  Integer newOwner "At an impact: the impacting ball-table constraint that gives newScale, else the current owner";
  discrete Integer owner(start=0, fixed=true) "Ball-table constraint whose impact set the current time scale (0: none, scale 1)";
  Boolean ownerReset "The owner lands or launches: the time scale returns to 1";
  Integer impacts(start=0, fixed=true) "Number of impact instants so far";
equation
  for i in 1:n loop
    connect(Table.OutPorts[i], TableContact[i].InPortA);
    connect(TableContact[i].OutPortA, Table.InPorts[i]);
    connect(Ball[i].OutPorts[1], TableContact[i].InPortB);
    connect(TableContact[i].OutPortB, Ball[i].InPorts[1]);
    connect(TableContact[i].OutImpactSignalB, Ball[i].InImpactSignals[1]);
  end for;
  // balls 1 - 2
  connect(Ball[1].OutPorts[2], BallContact[1].InPortA);
  connect(BallContact[1].OutPortA, Ball[1].InPorts[2]);
  connect(BallContact[1].OutImpactSignalA, Ball[1].InImpactSignals[2]);
  connect(Ball[2].OutPorts[2], BallContact[1].InPortB);
  connect(BallContact[1].OutPortB, Ball[2].InPorts[2]);
  connect(BallContact[1].OutImpactSignalB, Ball[2].InImpactSignals[2]);
  // balls 1 - 3
  connect(Ball[1].OutPorts[3], BallContact[2].InPortA);
  connect(BallContact[2].OutPortA, Ball[1].InPorts[3]);
  connect(BallContact[2].OutImpactSignalA, Ball[1].InImpactSignals[3]);
  connect(Ball[3].OutPorts[2], BallContact[2].InPortB);
  connect(BallContact[2].OutPortB, Ball[3].InPorts[2]);
  connect(BallContact[2].OutImpactSignalB, Ball[3].InImpactSignals[2]);
  // balls 2 - 3
  connect(Ball[2].OutPorts[3], BallContact[3].InPortA);
  connect(BallContact[3].OutPortA, Ball[2].InPorts[3]);
  connect(BallContact[3].OutImpactSignalA, Ball[2].InImpactSignals[3]);
  connect(Ball[3].OutPorts[3], BallContact[3].InPortB);
  connect(BallContact[3].OutPortB, Ball[3].InPorts[3]);
  connect(BallContact[3].OutImpactSignalB, Ball[3].InImpactSignals[3]);

  der(deltat) = 0;
  der(t) = deltat/TimeScale;
  // Time regularisation (paper A, 2.5) for several constraints: the whole model rescales
  // together (Remark 3.1). At any impact every Active and deltat are reinit to newScale:
  // at a ball-table impact the predicted scale min(1, 2|v_rn/a_rn|) of that constraint (the
  // smallest if several impact at once), which becomes the owner of the scale; at a
  // ball-ball impact the current scale (see the algorithm section). Only the owner's
  // landing or launch resets the scale to 1: the Launching signal of another constraint
  // (e.g. two balls accelerating apart while ball 1 bounces) would otherwise undo the
  // regularisation at once.
  when {TableContact[1].Impact, TableContact[2].Impact, TableContact[3].Impact,
        BallContact[1].Impact, BallContact[2].Impact, BallContact[3].Impact} then
    owner = newOwner;
    reinit(deltat, newScale);
    for i in 1:n loop
      reinit(Ball[i].Active, newScale);
      reinit(TableContact[i].Active, newScale);
    end for;
    for i in 1:3 loop
      reinit(BallContact[i].Active, newScale);
    end for;
  elsewhen ownerReset then
    owner = 0;
    reinit(deltat, 1);
    for i in 1:n loop
      reinit(Ball[i].Active, 1);
      reinit(TableContact[i].Active, 1);
    end for;
    for i in 1:3 loop
      reinit(BallContact[i].Active, 1);
    end for;
  end when;
  when {TableContact[1].Impact, TableContact[2].Impact, TableContact[3].Impact,
        BallContact[1].Impact, BallContact[2].Impact, BallContact[3].Impact} then
    impacts = pre(impacts) + 1;
  end when;
  when t >= tStop then
    terminate("physical stop time reached");
  end when;
algorithm
  // Only ball-table impacts change the time scale: their normal acceleration (gravity)
  // predicts the next impact, 2|v_rn/a_rn|. A ball-ball impact on the table has no such
  // steady normal acceleration: it keeps the current scale and owner.
  newScale := 1;
  newOwner := 0;
  for i in 1:n loop
    if TableContact[i].Impact then
      if newOwner == 0 or noEvent(2*abs(TableContact[i].relvn) < newScale*abs(TableContact[i].relan)) then
        newScale := min(1, 2*abs(TableContact[i].relvn)/max(abs(TableContact[i].relan), 1e-12));
        newOwner := i;
      end if;
    end if;
  end for;
  if newOwner == 0 then
    newScale := deltat;
    newOwner := owner;
  end if;
  ownerReset := false;
  for i in 1:n loop
    if owner == i then
      ownerReset := TableContact[i].StateIndicator > 0.5 or TableContact[i].Launching;
    end if;
  end for;
  // Tolerance 1e-9: with unimo at the time of writing, 1e-6, 1e-7 and 1e-9 run to tStop;
  // 1e-8 stops with "event iteration did not converge" (BallContact[1].Launching flips on
  // rounding noise of relan at its own zero crossing) and 1e-10 with "chattering" (relan of
  // two uniformly rolling balls is zero up to rounding).
  annotation (experiment(StartTime=0, StopTime=1000, Tolerance=1e-9));
end ThreeBallsOnTable;
