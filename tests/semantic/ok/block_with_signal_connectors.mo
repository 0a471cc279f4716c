// A block whose connectors all have a causality.
connector Signal
  input Real s;
end Signal;
connector RealOutput = output Real;
block B
  Signal u;
  RealOutput y;
equation
  y = u.s;
end B;
