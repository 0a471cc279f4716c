// Connections of neighbouring elements in a for loop.
connector Pin
  Real v;
  flow Real i;
end Pin;
partial model Node "partial: checked, not flattened (its pins are unconnected)"
  Pin p[3];
equation
  for i in 1:2 loop
    connect(p[i], p[i + 1]);
  end for;
end Node;
