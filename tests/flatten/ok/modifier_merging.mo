model Inner
  parameter Real k = 1;
  parameter Real offset = 0;
  Real y(start = 5, nominal = 10);
equation
  y = k * time + offset;
end Inner;

model Middle
  Inner a(k = 2, y(start = 6));
  Inner b(offset = 3);
end Middle;

model ModifierMerging "outer modifiers win over inner ones"
  Middle m(a(k = 4), b(y(nominal = 1)));
  Inner c(final k = 7);
end ModifierMerging;
