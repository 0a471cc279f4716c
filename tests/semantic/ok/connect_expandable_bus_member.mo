// A member of an expandable connector, declared in it.
expandable connector Bus
  Real signal;
end Bus;
connector RealOutput = output Real;
block Source
  RealOutput y = 1;
end Source;
connector RealInput = input Real;
block Sink
  RealInput u;
  output Real y = u;
end Sink;
model M
  Bus bus;
  Source s;
  Sink k;
equation
  connect(s.y, bus.signal);
  connect(bus.signal, k.u);
end M;
