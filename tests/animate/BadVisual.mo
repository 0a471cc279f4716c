model BadVisual "A body class whose annotation names a variable it does not have"
  model Thing
    Real r[3] = {0, 0, time};
    parameter Real radius = 0.1;
    annotation(__unimo_visual(shape = "sphere", size = {radius}, position = rr));
  end Thing;
  Thing thing;
end BadVisual;
