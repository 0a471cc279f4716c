within Modelica.Blocks.Interfaces;
connector BooleanInPort "Connector with input signals of type Boolean"
  // MSL 1.x connector (signal vector of size n); MSL 2.x and later use BooleanInput
  parameter Integer n = 1 "Dimension of signal vector";
  input Boolean signal[n] "Boolean input signals";
end BooleanInPort;
