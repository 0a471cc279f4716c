within Modelica.Blocks.Interfaces;
connector InPort "Connector with input signals of type Real"
  // MSL 1.x connector (signal vector of size n); MSL 2.x and later use RealInput
  parameter Integer n = 1 "Dimension of signal vector";
  replaceable type SignalType = Real "type of signal";
  input SignalType signal[n] "Real input signals";
end InPort;
