model MarkeevEllipsoid "Example 3 of paper A: Markeev's rising ellipsoid; fast spin lifts the centre of mass from b = 1 to c = 1.3"
  // Data: spec A.9, example 3.
  extends UnilateralMBS.Examples.EllipsoidOnPlane(
    a=1.2, b=1, c=1.3, g=9.81, k=0.5, f=0.01, delta=1e-4, ClearanceTolerance=1e-8,
    r0={0, 1, 0}, Clearance0=0, v0={0.05, 0, 0}, omega0={0, -10, 2}, tStop=160);
  annotation (experiment(StartTime=0, StopTime=1e6, Tolerance=1e-8));
end MarkeevEllipsoid;
