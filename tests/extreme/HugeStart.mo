model HugeStart "start values of 1e300: x = 1e300 exp(-t), z = -1e300 + t"
  Real x(start = 1e300, fixed = true);
  Real z(start = -1e300, fixed = true);
equation
  der(x) = -x;
  der(z) = 1;
  annotation(experiment(StopTime = 1));
end HugeStart;
