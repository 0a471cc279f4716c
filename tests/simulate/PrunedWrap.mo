// A held rounding in a step no requested output needs: `wrapped = mod(phi, 2 pi)` of
// an angle turning at 1 rad/s. Simulated with only `phi` requested, the step of
// `wrapped` is still evaluated at events (it updates the held value of the rounding;
// left out, the rounding's bound was crossed again at once: E4006 chattering).
model PrunedWrap
  Real phi(start = 0, fixed = true);
  Real wrapped;
equation
  der(phi) = 1;
  wrapped = mod(phi, 2 * 3.141592653589793);
  annotation(experiment(StopTime = 20));
end PrunedWrap;
