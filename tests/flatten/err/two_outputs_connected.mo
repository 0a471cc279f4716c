block Source
  output Real y;
equation
  y = time;
end Source;

model TwoOutputsConnected
  Source s1, s2;
equation
  connect(s1.y, s2.y);
end TwoOutputsConnected;
