// A realistic acausal electrical circuit: series RLC driven by a sine source.
within;

package Electrical "Minimal analog library"
  type Voltage = Real(unit = "V");
  type Current = Real(unit = "A");
  constant Real pi = 3.141592653589793;

  connector Pin "Electrical pin"
    Voltage v "Potential at the pin";
    flow Current i "Current flowing into the pin";
  end Pin;

  partial model OnePort "Component with two electrical pins"
    Pin p "Positive pin";
    Pin n "Negative pin";
    Voltage v "Voltage drop p.v - n.v";
    Current i "Current from p to n";
  equation
    v = p.v - n.v;
    0 = p.i + n.i;
    i = p.i;
  end OnePort;

  model Resistor
    extends OnePort;
    parameter Real R(unit = "Ohm") = 1;
  equation
    v = R * i;
  end Resistor;

  model Capacitor
    extends OnePort(v(start = 0, fixed = true));
    parameter Real C(unit = "F") = 1e-3;
  equation
    i = C * der(v);
  end Capacitor;

  model Inductor
    extends OnePort(i(start = 0, fixed = true));
    parameter Real L(unit = "H") = 1e-2;
  equation
    L * der(i) = v;
  end Inductor;

  model SineVoltage
    extends OnePort;
    parameter Voltage V = 10 "Amplitude";
    parameter Real f(unit = "Hz") = 50 "Frequency";
  equation
    v = V * sin(2 * pi * f * time);
  end SineVoltage;

  model Ground
    Pin p;
  equation
    p.v = 0;
  end Ground;
end Electrical;

model RLCCircuit "Series RLC circuit"
  import Electrical.*;
  SineVoltage source(V = 230, f = 50);
  Resistor resistor(R = 10);
  Inductor inductor(L = 0.1);
  Capacitor capacitor(C = 1e-4);
  Ground ground;
equation
  connect(source.p, resistor.p);
  connect(resistor.n, inductor.p);
  connect(inductor.n, capacitor.p);
  connect(capacitor.n, source.n);
  connect(source.n, ground.p);
  annotation(experiment(StartTime = 0, StopTime = 0.2, Tolerance = 1e-6, Interval = 1e-4));
end RLCCircuit;
