package OverLib "an overdetermined record in connectors (spec 9.4)"
  record Angle "a planar orientation: two numbers for one angle"
    Real c "cosine";
    Real s "sine";
    function equalityConstraint "one residue for two orientations"
      input Angle a;
      input Angle b;
      output Real residue[1];
    algorithm
      residue := {a.s * b.c - a.c * b.s};
    end equalityConstraint;
  end Angle;

  connector Frame
    Angle R;
    flow Real t "torque";
  end Frame;

  model Ground "the definite root"
    Frame frame;
    Real k "the number of connections to the frame";
  equation
    Connections.root(frame.R);
    frame.R = Angle(1, 0);
    k = cardinality(frame);
  end Ground;

  model Link "a rigid link: a branch of the graph"
    Frame a;
    Frame b;
    Real x "1 when frame a is nearer the root";
  equation
    Connections.branch(a.R, b.R);
    b.R = a.R;
    a.t + b.t = 0;
    x = if Connections.rooted(a.R) then 1 else 2;
  end Link;

  model Body "its angle drives the frame when the frame is a root"
    Frame frame;
    Real phi(start = 0.5, fixed = true);
  equation
    Connections.potentialRoot(frame.R);
    if Connections.isRoot(frame.R) then
      frame.R = Angle(cos(phi), sin(phi));
    else
      frame.t = phi;
    end if;
    der(phi) = 1;
  end Body;
end OverLib;

model OverconstrainedConnections "a loop of links broken by equalityConstraint, roots and cardinality"
  OverLib.Ground ground;
  OverLib.Link link1;
  OverLib.Link link2;
  OverLib.Body free "its own part: the root";
  OverLib.Body attached "connected to the ground: not a root";
equation
  connect(ground.frame, link1.a);
  connect(link1.b, link2.a);
  connect(link2.b, ground.frame);
  connect(attached.frame, ground.frame);
end OverconstrainedConnections;
