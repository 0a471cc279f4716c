// `connector RealInput = input Real`: the prefix of a short class definition gives its
// components their causality. A block whose input comes through such a connector is
// balanced on its own (the top-level input is known), and nested instances keep the
// causality for their enclosing model's connections.
block ShortClassCausality
  connector RealInput = input Real "an input signal";
  connector RealOutput = output Real "an output signal";
  type Voltages = Real[2](each unit = "V");
  connector VoltagesInput = input Voltages;
  block Gain
    parameter Real k = 2;
    RealInput u;
    RealOutput y;
  equation
    y = k * u;
  end Gain;
  RealInput u;
  VoltagesInput w;
  RealOutput y;
  RealOutput z;
  Real s(start = 0, fixed = true);
  Gain g;
equation
  g.u = u + w[1] - w[2];
  y = g.y;
  der(s) = y;
  z = 2 * s;
end ShortClassCausality;
