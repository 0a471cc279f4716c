within Modelica.Blocks.Interfaces;
connector RealOutPort = OutPort
  "Connector with output signals of type Real (not an MSL name: alias of the MSL 1.x OutPort)";
