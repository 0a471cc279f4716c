// A parameter in a block's connector needs no causality.
connector Signal
  parameter Real scale = 1;
  input Real s;
end Signal;
block B
  Signal u;
  output Real y;
equation
  y = u.scale*u.s;
end B;
