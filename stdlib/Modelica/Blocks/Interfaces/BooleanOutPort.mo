within Modelica.Blocks.Interfaces;
connector BooleanOutPort "Connector with output signals of type Boolean"
  // MSL 1.x connector (signal vector of size n); MSL 2.x and later use BooleanOutput
  parameter Integer n = 1 "Dimension of signal vector";
  output Boolean signal[n] "Boolean output signals";
end BooleanOutPort;
