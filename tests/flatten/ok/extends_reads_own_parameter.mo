// An extends modifier that reads a parameter the class itself declares
// (`extends HeatPort(useHeatPort = useTemperature)`): the base's conditional component
// needs its value while the base is instantiated, before the class's own elements.
package OwnParameter
  connector HeatPort
    Real T;
    flow Real Q_flow;
  end HeatPort;

  partial model ConditionalHeatPort
    parameter Boolean useHeatPort = false;
    parameter Real T = 293.15 "fixed temperature without a port";
    HeatPort heatPort if useHeatPort;
  end ConditionalHeatPort;

  model Device
    parameter Boolean useTemperature = true;
    extends ConditionalHeatPort(useHeatPort = useTemperature);
    Real x(start = 1, fixed = true);
  equation
    der(x) = -x;
  end Device;
end OwnParameter;

model ExtendsReadsOwnParameter
  OwnParameter.Device withPort;
  OwnParameter.Device withoutPort(useTemperature = false);
equation
  withPort.heatPort.T = 300;
end ExtendsReadsOwnParameter;
