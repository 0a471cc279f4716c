// Consistent and inconsistent starts of the mechanisms in models/ (tests/state_selection.rs).
// Consistent: some coordinates fixed, the others free with rough guesses; the
// initialization solves the constraints and their differentiated (hidden) forms.
model PendulumFreeY = PendulumCartesian(x(start = 0.6), y(start = -0.7, fixed = false), vx(start = 0.3), vy(fixed = false));
model DoublePendulumFree = DoublePendulumCartesian(x1(start = 0.6), y1(start = -0.7, fixed = false), x2(start = 1.2), y2(start = -1.3, fixed = false), vx1(start = 0.5), vy1(fixed = false), vx2(start = -0.2), vy2(fixed = false));
// Inconsistent: fixed values that contradict a constraint.
model PendulumPositionOff = PendulumCartesian(x(start = 0.6), y(start = -0.5));
model PendulumVelocityOff = PendulumCartesian(phi0 = 0.6435011087932844, vx(start = 1), vy(start = 1));
model DoublePendulumRodOff = DoublePendulumCartesian(x2(start = 1.5));
model FourBarOff = FourBar(yB(fixed = true, start = 0.9));
model SliderCrankOff = SliderCrank(yC(fixed = true, start = 0.1));
