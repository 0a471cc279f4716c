package Extremes "Stability on extreme cases of paper A's scene (tests/paper_a.rs): each must finish without chattering, step-size collapse or energy gain, or fail with a documented diagnostic"
  model Base "Ellipsoid dropped spinning on the plane, 12 s of physical time: flight, bounces, landing, sliding"
    extends UnilateralMBS.Examples.EllipsoidOnPlane(
      a=1.0, b=0.8, c=1.2, g=1, k=0.6, f=0.08, delta=1e-3, ClearanceTolerance=1e-8,
      r0={0, 2, 0}, v0={0.05, 0, 0}, omega0={0, -10, 2}, tStop=12);
    annotation (experiment(StopTime=1e6, Tolerance=1e-8));
  end Base;
  model PlasticImpacts "k = 0: the first impact lands"
    extends Base(k=0);
  end PlasticImpacts;
  model ElasticImpacts "k = 1: no normal loss, bounces never decay by restitution"
    extends Base(k=1);
  end ElasticImpacts;
  model Frictionless "f = 0"
    extends Base(f=0);
  end Frictionless;
  model HighFriction "f = 10"
    extends Base(f=10);
  end HighFriction;
  model TinyDelta "delta = 1e-8: nearly unregularised Coulomb friction"
    extends Base(delta=1e-8);
  end TinyDelta;
  model FastSpin "omega = 1e3 about the body y axis"
    extends Base(omega0={0, -1e3, 2}, tStop=2);
  end FastSpin;
  model Sphere "a = b = c: an ellipsoid that is a sphere"
    extends Base(a=1, b=1, c=1);
  end Sphere;
  model FlatEllipsoid "c = 0.01: a nearly flat disc"
    extends Base(c=0.01);
  end FlatEllipsoid;
  model TinyClearance "ClearanceTolerance = 1e-15, near machine precision"
    extends Base(ClearanceTolerance=1e-15);
  end TinyClearance;
  model LongHorizon "resting and sliding to t = 1e4"
    extends Base(r0={0, 0.8, 0}, Clearance0=0, omega0={0, -2, 2}, v0={0.3, 0, 0}, tStop=1e4);
  end LongHorizon;
end Extremes;
