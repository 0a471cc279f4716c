// A realistic discretized model: heat conduction along a rod using arrays
// of connectors and components connected in a for-loop.
within;

connector HeatPort "Thermal port"
  Real T(unit = "K") "Port temperature";
  flow Real Q_flow(unit = "W") "Heat flow rate into the component";
end HeatPort;

model HeatCapacitor "Lumped thermal capacity"
  parameter Real C = 10 "Heat capacity";
  parameter Real T0 = 293.15 "Initial temperature";
  Real T(start = T0, fixed = true, nominal = 300) "Temperature";
  HeatPort port;
equation
  port.T = T;
  C * der(T) = port.Q_flow;
end HeatCapacitor;

model ThermalConductor "Lossless thermal conductance"
  parameter Real G = 1 "Conductance";
  HeatPort port_a;
  HeatPort port_b;
  Real Q_flow "Heat flow from a to b";
equation
  Q_flow = G * (port_a.T - port_b.T);
  port_a.Q_flow = Q_flow;
  port_b.Q_flow = -Q_flow;
end ThermalConductor;

model FixedTemperature "Boundary with prescribed temperature"
  parameter Real T = 373.15;
  HeatPort port;
equation
  port.T = T;
end FixedTemperature;

model Rod "Rod discretized into n segments"
  parameter Integer n(min = 2) = 10 "Number of segments";
  parameter Real L = 1 "Length";
  parameter Real lambda = 50 "Thermal conductivity";
  parameter Real area = 1e-4 "Cross-section area";
  HeatCapacitor seg[n](each C = 100 / n, T0 = {293.15 + i for i in 1:n});
  ThermalConductor cond[n - 1](each G = lambda * area / (L / n));
  FixedTemperature hot(T = 373.15);
  ThermalConductor contact(G = 1);
  Real Tmean "Mean rod temperature";
equation
  connect(hot.port, contact.port_a);
  connect(contact.port_b, seg[1].port);
  for i in 1:n - 1 loop
    connect(seg[i].port, cond[i].port_a);
    connect(cond[i].port_b, seg[i + 1].port);
  end for;
  Tmean = sum(seg[i].T for i in 1:n) / n;
  annotation(experiment(StopTime = 100, Interval = 0.1));
end Rod;
