// Annotations on classes, components, extends clauses, connect equations,
// short classes and functions, including graphics, documentation,
// dialogs, choices, experiment settings and vendor-specific annotations.
type Resistance = Real(unit = "Ohm", min = 0) "Electrical resistance"
  annotation(Documentation(info = "<html><p>Resistance type.</p></html>"));

connector Pin "Electrical pin"
  Real v "Potential";
  flow Real i "Current";
  annotation(Icon(graphics = {Rectangle(extent = {{-100, 100}, {100, -100}},
    lineColor = {0, 0, 255}, fillColor = {0, 0, 255}, fillPattern = FillPattern.Solid)}));
end Pin;

partial model OnePort "Two pins"
  Pin p annotation(Placement(transformation(extent = {{-110, -10}, {-90, 10}})));
  Pin n annotation(Placement(transformation(extent = {{90, -10}, {110, 10}}),
    iconTransformation(extent = {{90, -10}, {110, 10}})));
  Real v = p.v - n.v;
  Real i = p.i;
equation
  0 = p.i + n.i;
end OnePort;

function limit "Clamp a value"
  input Real x;
  input Real lo;
  input Real hi;
  output Real y;
algorithm
  y := min(max(x, lo), hi);
  annotation(Inline = true, smoothOrder = 0, __OpenModelica_Comment = "vendor");
end limit;

model AnnotatedResistor "Resistor with annotations"
  extends OnePort annotation(IconMap(primitivesVisible = true));
  parameter Resistance R = 100 "Resistance"
    annotation(Dialog(group = "Parameters", enable = true), Evaluate = true);
  parameter Boolean useLimit = false
    annotation(choices(checkBox = true), Dialog(tab = "Advanced"));
  parameter Integer mode = 1 "Model variant"
    annotation(choices(choice = 1 "Linear", choice = 2 "Quadratic"));
  Real power annotation(HideResult = false);
equation
  v = R * (if useLimit then limit(i, -1, 1) else i);
  power = v * i;
  annotation(
    Icon(coordinateSystem(preserveAspectRatio = true, extent = {{-100, -100}, {100, 100}}),
      graphics = {
        Rectangle(extent = {{-70, 30}, {70, -30}}, lineColor = {0, 0, 255},
          fillColor = {255, 255, 255}, fillPattern = FillPattern.Solid),
        Line(points = {{-90, 0}, {-70, 0}}, color = {0, 0, 255}),
        Text(extent = {{-150, 90}, {150, 50}}, textString = "%name", textColor = {0, 0, 255})}),
    Diagram(coordinateSystem(extent = {{-100, -100}, {100, 100}})),
    Documentation(info = "<html>
<p>A resistor with <b>annotations</b> and \"quoted\" text.</p>
</html>", revisions = "<html><ul><li>First version</li></ul></html>"),
    experiment(StartTime = 0, StopTime = 1, Tolerance = 1e-6, Interval = 0.01),
    __OpenModelica_simulationFlags(s = "dassl", lv = "LOG_STATS"));
end AnnotatedResistor;

model Ground "Zero potential"
  Pin p annotation(Placement(transformation(extent = {{-10, 90}, {10, 110}})));
equation
  p.v = 0;
  annotation(Icon(graphics = {Line(points = {{-60, 50}, {60, 50}}, color = {0, 0, 255})}));
end Ground;

model SineSource "Sinusoidal voltage source"
  extends OnePort;
  parameter Real V = 1 "Amplitude";
equation
  v = V * sin(time) annotation(__unimo_note = "annotation on an equation");
end SineSource;

model AnnotatedCircuit "Series circuit with placement and line annotations"
  SineSource src(V = 230) annotation(Placement(transformation(origin = {-40, 0},
    extent = {{-10, -10}, {10, 10}}, rotation = 270)));
  AnnotatedResistor r1(R = 10) annotation(Placement(transformation(extent = {{-10, 10}, {10, 30}})));
  AnnotatedResistor r2(R = 20) annotation(Placement(transformation(extent = {{20, 10}, {40, 30}})));
  Ground ground annotation(Placement(transformation(extent = {{-50, -40}, {-30, -20}})));
equation
  connect(src.p, r1.p) annotation(Line(points = {{-40, 10}, {-10, 20}}, color = {0, 0, 255}));
  connect(r1.n, r2.p) annotation(Line(points = {{10, 20}, {20, 20}}, color = {0, 0, 255}, thickness = 0.5));
  connect(r2.n, src.n) "Return path" annotation(Line(points = {{40, 20}, {50, -10}, {-40, -10}}));
  connect(src.n, ground.p);
  annotation(experiment(StopTime = 0.1, Interval = 1e-4));
end AnnotatedCircuit;
