// Component declarations: all type prefixes, attribute modifiers,
// declaration equations, several components per declaration, descriptions.
connector HeatPort "Thermal port"
  Real T(unit = "K") "Temperature";
  flow Real Q_flow(unit = "W") "Heat flow into the component";
end HeatPort;

model ThermalMass "Lumped thermal capacity"
  constant Real cp_water = 4186 "Specific heat of water";
  parameter Real m(min = 0, max = 1e4, unit = "kg") = 2.5 "Mass";
  parameter Real C = m * cp_water "Heat capacity";
  final parameter Real invC = 1 / C "Cannot be modified";
  Real T(start = 293.15, fixed = true, unit = "K", nominal = 300, min = 0,
    max = 1000, stateSelect = StateSelect.prefer) "Temperature";
  Real dT "Temperature derivative";
  HeatPort port;
  discrete Real T_sampled(start = 293.15, fixed = true) "Sampled temperature";
  discrete Integer samples(start = 0, fixed = true) "Number of samples";
  output Real T_degC = T - 273.15 "Temperature in degrees Celsius";
equation
  port.T = T;
  dT = der(T);
  dT = invC * port.Q_flow;
  when sample(0, 1) then
    T_sampled = T;
    samples = pre(samples) + 1;
  end when;
end ThermalMass;

model Heater "Heat source driven by a control signal"
  parameter Real Q_nom = 1000 "Nominal heat flow";
  input Real onOff(min = 0, max = 1) "Control signal";
  output Real Q "Delivered heat flow";
  HeatPort port;
equation
  Q = Q_nom * onOff;
  port.Q_flow = -Q;
end Heater;

model HeatingSystem "Top-level model"
  parameter Boolean enabled = true;
  parameter String title = "Heating demo";
  constant Integer N = 2;
  ThermalMass tank(m = 10, T(start = 290));
  Heater heater(Q_nom = 2000, onOff = if enabled and tank.T < 300 then 1 else 0);
  Real a, b(start = 1, nominal = 2), c "Three variables in one declaration";
  Integer k = N + 1;
  Boolean hot = tank.T > 310;
  Real gains[N] = {1.5, 2.5};
equation
  connect(heater.port, tank.port);
  a = gains[1];
  b = 2 * a;
  c = a + b;
end HeatingSystem;
