// Connectors with potential and flow variables, partial base models,
// connect equations on scalars and array elements, connect in for-loops.
connector Flange "One-dimensional translational flange"
  Real s(unit = "m") "Absolute position";
  flow Real f(unit = "N") "Cut force";
end Flange;

partial model TwoFlanges "Component with two flanges"
  Flange flange_a "Left flange";
  Flange flange_b "Right flange";
end TwoFlanges;

model Mass "Sliding mass"
  extends TwoFlanges;
  parameter Real m(min = 0) = 1;
  Real s(start = 0, fixed = true);
  Real v(start = 0, fixed = true);
equation
  flange_a.s = s;
  flange_b.s = s;
  der(s) = v;
  m * der(v) = flange_a.f + flange_b.f;
end Mass;

model Spring "Linear spring"
  extends TwoFlanges;
  parameter Real c(min = 0) = 100 "Stiffness";
  parameter Real s_rel0 = 0 "Unstretched length";
  Real s_rel;
  Real f;
equation
  s_rel = flange_b.s - flange_a.s;
  f = c * (s_rel - s_rel0);
  flange_b.f = f;
  flange_a.f = -f;
end Spring;

model Fixed "Fixed point"
  parameter Real s0 = 0;
  Flange flange;
equation
  flange.s = s0;
end Fixed;

model Force "External force"
  Flange flange;
  input Real f "Driving force";
equation
  flange.f = -f;
end Force;

model MassChain "Masses connected by springs"
  parameter Integer n = 3;
  Fixed wall;
  Spring springs[n](each c = 50);
  Mass masses[n](m = {1, 2, 3});
  Force force(f = sin(time));
equation
  connect(wall.flange, springs[1].flange_a);
  for i in 1:n loop
    connect(springs[i].flange_b, masses[i].flange_a);
  end for;
  for i in 1:n - 1 loop
    connect(masses[i].flange_b, springs[i + 1].flange_a);
  end for;
  connect(masses[n].flange_b, force.flange)
    annotation(Line(points = {{40, 0}, {60, 0}}, color = {0, 127, 0}));
  annotation(experiment(StopTime = 10));
end MassChain;
