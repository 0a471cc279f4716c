// Release conditions of the Cartesian pendulum (models/PendulumCartesian.mo) and of its
// reference in tests/state_selection/References.mo.
model PendulumHorizontal = PendulumCartesian(phi0 = 1.5707963267948966);
model PendulumUpright = PendulumCartesian(phi0 = 3.1405926535897932);
model PendulumRotating = PendulumCartesian(phi0 = 0, w0 = 7);
model AngleHorizontal = PendulumAngle(phi0 = 1.5707963267948966);
model AngleUpright = PendulumAngle(phi0 = 3.1405926535897932);
model AngleRotating = PendulumAngle(phi0 = 0, w0 = 7);
model PendulumAt05 = PendulumCartesian(phi0 = 0.5);
model PendulumAt10 = PendulumCartesian(phi0 = 1.0);
model PendulumAt20 = PendulumCartesian(phi0 = 2.0);
model PendulumAt30 = PendulumCartesian(phi0 = 3.0);
model PendulumAt31 = PendulumCartesian(phi0 = -3.1, w0 = -1);
