model FlySlideRoll "Example 1 of paper A: a heavy spinning ellipsoid flies, bounces thousands of times, slides, sticks and slips, and finally rolls (t in [0, 150])"
  // Data: spec A.9 (chosen there, the paper does not print them), ClearanceTolerance
  // 1e-12 included: with the closest points in closed form (change S10 of
  // docs/paper-a-transcription.md) the bounces land at this tolerance.
  extends UnilateralMBS.Examples.EllipsoidOnPlane(
    a=1.0, b=0.8, c=1.2, g=1, k=0.6, f=0.08, delta=1e-3, ClearanceTolerance=1e-12,
    r0={0, 5, 0}, v0={0.05, 0, 0}, omega0={0, -10, 2}, tStop=150);
  // Radau5: its event times carry the accuracy of its steps (docs/results/paper-a.md), and
  // it takes a tenth of BDF's steps here; `--method` still chooses another.
  annotation (experiment(StartTime=0, StopTime=1e6, Tolerance=1e-8, __unimo_method="radau5"));
end FlySlideRoll;
