package P
  import SI = Modelica.SIunits;
  constant Real k = 2;
  type Speed = SI.Velocity;
  partial model Base
    Speed v;
    parameter Real gain = k "constant of the enclosing package";
  end Base;
  model Derived
    extends Base;
    import Modelica.Constants.*;
    Real y;
  equation
    v = gain * pi;
    y = der(v) + g_n;
  end Derived;
  encapsulated model Sealed
    import P.Base;
    import Modelica.Units.SI.{Length, Mass};
    Base b;
    Length l;
    Mass m;
  end Sealed;
end P;
