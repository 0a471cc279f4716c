model OwnBody "A user's own body class: a cone spinning about world z and a box sliding, drawn through their annotations"
  model Spinner
    parameter Real radius = 0.2;
    parameter Real height = 0.5;
    parameter Real omega = 2;
    Real angle(start = 0, fixed = true);
    Real q[4] = {cos(angle / 2), 0, 0, sin(angle / 2)} "w, x, y, z";
  equation
    der(angle) = omega;
    annotation(__unimo_visual(shape = "cone", size = {radius, height}, position = {0, 0, 0}, quaternion = q, color = "#cc3333"));
  end Spinner;
  model Slider
    parameter Real edge = 0.3;
    Real x(start = -1, fixed = true);
  equation
    der(x) = 2;
    annotation(__unimo_visual(shape = "box", size = {edge, edge, edge}, position = {x, 0.8, 0}));
  end Slider;
  Spinner spinner;
  Slider slider(edge = 0.25);
  annotation(experiment(StopTime = 1, Interval = 0.05));
end OwnBody;
