within Modelica.Blocks.Interfaces;
connector RealInPort = InPort
  "Connector with input signals of type Real (not an MSL name: alias of the MSL 1.x InPort)";
