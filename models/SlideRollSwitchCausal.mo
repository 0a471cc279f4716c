model SlideRollSwitchCausal "Causal reference of SlideRollSwitch (same data; constraint state switched in when-clauses). Example 2 of paper A: an ellipsoid resting on the plane switches between sliding and rolling"
  // Data: spec A.9, example 2 (r(0) = (0, 1, 0): resting on its semi-axis b = 1).
  extends UnilateralMBS.Examples.EllipsoidOnPlaneCausal(
    a=1.2, b=1, c=1.3, g=9.81, k=0.5, f=0.1, delta=1e-4, ClearanceTolerance=1e-8,
    r0={0, 1, 0}, Clearance0=0, v0={0.05, 0, 0}, omega0={0, -2, 2}, tStop=20);
  annotation (experiment(StartTime=0, StopTime=1e6, Tolerance=1e-8));
end SlideRollSwitchCausal;
