model HomotopyStart "A limited op-amp in positive feedback: at the start values (0) the loop has three solutions, -15, 0 and 15; homotopy's simplified model (the lower limit) selects -15, as the MSL's IdealizedOpAmpLimited with homotopyType = LowerLimit asks"
  parameter Real V0 = 15000;
  Real vin "input difference";
  Real vout "output";
  Real x(start = 0, fixed = true);
equation
  der(x) = 1;
  vin = 0.5 * vout - 0.1 * x;
  vout = homotopy(actual = smooth(0, noEvent(if V0 * vin > 15 then 15 else if V0 * vin < -15 then -15 else V0 * vin)), simplified = -15);
end HomotopyStart;
