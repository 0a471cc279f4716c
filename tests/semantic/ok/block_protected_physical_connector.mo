// A block may use a physical connector in its protected part.
connector Pin
  Real v;
  flow Real i;
end Pin;
block B
  output Real y;
protected
  Pin p;
equation
  p.v = 1;
  y = p.v;
end B;
