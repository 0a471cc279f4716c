model LimitedOpAmp "A non-inverting amplifier with the MSL's limited op-amp law (gain 15000, output within +-15 V): Newton must not bounce between the saturated parts"
  parameter Real V0 = 15000;
  parameter Real Vps = 15, Vns = -15;
  parameter Real R1 = 1000, R2 = 1000;
  Real vin, vn, vout, i;
equation
  vin = sin(2 * 3.14159 * time);
  vout = smooth(0, noEvent(if V0 * (vin - vn) > Vps then Vps else if V0 * (vin - vn) < Vns then Vns else V0 * (vin - vn)));
  i = (vout - vn) / R2;
  vn = i * R1;
end LimitedOpAmp;
