within Modelica.Blocks.Interfaces;
connector OutPort "Connector with output signals of type Real"
  // MSL 1.x connector (signal vector of size n); MSL 2.x and later use RealOutput
  parameter Integer n = 1 "Dimension of signal vector";
  replaceable type SignalType = Real "type of signal";
  output SignalType signal[n] "Real output signals";
end OutPort;
