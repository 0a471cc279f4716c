// Short connectors (`connector RealInput = input Real`).
connector RealInput = input Real;
connector RealOutput = output Real;
block Gain
  parameter Real k = 2;
  RealInput u;
  RealOutput y;
equation
  y = k*u;
end Gain;
block Const
  RealOutput y = 1;
end Const;
model M
  Gain g;
  Const c;
equation
  connect(c.y, g.u);
end M;
