// A type written in the long form that only extends a predefined type (the MSL's
// `Modelica.Icons.TypeReal`: `type TypeReal extends Real; annotation(...); end
// TypeReal;`) is that type: components of it are scalars that take its attributes, and
// types built on it by the short form keep their dimensions and modifiers. A nested
// function does not make it a structured class. A base met along two inheritance paths
// (a diamond, as `MultiBody.Visualizers.Advanced.Shape` extends `PartialShape` directly and
// through `ModelicaServices.Animation.Shape`) contributes its elements once, in every
// instance of the class (`b2`: the second instance once created them twice).
model LongTypesAndDiamonds
  type TypeReal "a Real with an icon"
    extends Real;
  end TypeReal;
  type TypeInteger
    extends Integer;
  end TypeInteger;
  type Angle = TypeReal(final unit = "rad");
  type Axis = TypeReal[3](each final unit = "1");
  type Color = TypeInteger[3](each min = 0, each max = 255);
  type QuaternionBase = Real[4];
  type Orientation "with its own function, as Quaternions.Orientation"
    extends QuaternionBase;
    function norm2
      input Real q[4];
      output Real n;
    algorithm
      n := q * q;
    end norm2;
  end Orientation;
  partial model Base
    parameter Real k = 2;
    Real x;
  end Base;
  model Middle
    extends Base;
  end Middle;
  model Both
    extends Middle;
    extends Base;
  equation
    x = k;
  end Both;
  parameter Angle phi = 0.5;
  parameter Axis n = {1, 0, 0};
  parameter Color c = {255, 0, 0};
  Orientation q(start = {1, 0, 0, 0});
  Both b;
  Both b2;
  Real s;
equation
  q = {cos(phi * time), sin(phi * time) * n[1], 0, 0};
  s = Orientation.norm2(q) + c[1];
end LongTypesAndDiamonds;
