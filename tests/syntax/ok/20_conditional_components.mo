// Conditional components: conditional connectors with the internal
// connector pattern, and conditional non-connector components.
connector RealInput = input Real;
connector RealOutput = output Real;

block Limiter "Limits the input; the limit may come from a conditional input"
  parameter Boolean useExternalLimit = false "= true to use the limit input";
  parameter Real fixedLimit = 1 "Used if useExternalLimit = false";
  parameter Boolean showDebug = true;
  RealInput u;
  RealInput limit if useExternalLimit "Conditional limit input";
  RealOutput y;
  Real excess = u - y if showDebug "Conditional plain component";
protected
  RealInput limit_internal "Needed to connect to the conditional connector";
equation
  connect(limit, limit_internal);
  if not useExternalLimit then
    limit_internal = fixedLimit;
  end if;
  y = max(-limit_internal, min(limit_internal, u));
end Limiter;

connector HeatPort
  Real T;
  flow Real Q_flow;
end HeatPort;

model LossyResistor "Resistor with an optional heat port"
  parameter Real R = 1;
  parameter Boolean useHeatPort = false;
  parameter Real T = 300 "Fixed temperature if useHeatPort = false";
  Real v = sin(time);
  Real i;
  Real lossPower;
  HeatPort heatPort(final Q_flow = -lossPower) if useHeatPort "Conditional with modifiers";
equation
  v = R * i;
  lossPower = v * i;
end LossyResistor;

model ConditionalDemo
  Limiter lim1(u = 2 * sin(time));
  Limiter lim2(useExternalLimit = true, u = 2 * sin(time), limit = 0.5 + 0.1 * time);
  LossyResistor r1;
  LossyResistor r2(useHeatPort = false);
end ConditionalDemo;
