model BadDelay "delay's time varies and no delayMax is given"
  Real x(start = 1, fixed = true);
equation
  der(x) = -delay(x, 1 + 0.1*time);
end BadDelay;
