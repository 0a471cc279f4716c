// A series RLC circuit from acausal components: connections create alias sets that
// alias elimination removes.
connector Pin
  Real v "Potential";
  flow Real i "Current into the pin";
end Pin;

partial model TwoPin
  Pin p, n;
  Real v "Voltage drop";
  Real i "Current from p to n";
equation
  v = p.v - n.v;
  0 = p.i + n.i;
  i = p.i;
end TwoPin;

model Resistor
  extends TwoPin;
  parameter Real R = 10;
equation
  v = R*i;
end Resistor;

model Capacitor
  extends TwoPin;
  parameter Real C = 1e-3;
equation
  C*der(v) = i;
end Capacitor;

model Inductor
  extends TwoPin;
  parameter Real L = 0.1;
equation
  L*der(i) = v;
end Inductor;

model ConstantVoltage
  extends TwoPin;
  parameter Real V = 1;
equation
  v = V;
end ConstantVoltage;

model Ground
  Pin p;
equation
  p.v = 0;
end Ground;

model RLCCircuit
  ConstantVoltage source(V = 10);
  Resistor resistor(R = 5);
  Inductor inductor(L = 0.2);
  Capacitor capacitor(C = 1e-2, v(start = 0, fixed = true));
  Ground ground;
equation
  connect(source.p, resistor.p);
  connect(resistor.n, inductor.p);
  connect(inductor.n, capacitor.p);
  connect(capacitor.n, source.n);
  connect(source.n, ground.p);
  annotation(experiment(StopTime = 2));
end RLCCircuit;
