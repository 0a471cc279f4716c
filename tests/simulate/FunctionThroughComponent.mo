package FunctionThroughComponent
  "functions called through a component (world.gravityAcceleration(r) in MultiBody) and short function classes with modifiers"
  partial function PartialField
    input Real r;
    output Real y;
  end PartialField;

  function Linear "y = k r + c"
    extends PartialField;
    input Real k;
    input Real c = 1;
  algorithm
    y := k*r + c;
  end Linear;

  function Square "y = a r^2"
    extends PartialField;
    input Real a;
  algorithm
    y := a*r*r;
  end Square;

  model World
    parameter Real g = 3;
    parameter Real n = 2;
    replaceable function field = Linear(k = g*n) constrainedby PartialField
      "its modifiers read the instance's parameters";
  end World;

  model Body
    outer World world;
    Real x(start = 1, fixed = true);
  equation
    der(x) = -world.field(x);
  end Body;

  model Default "der(x) = -(k x + 1), k = 0.5*2: x = 2 exp(-t) - 1"
    inner World world(g = 0.5);
    Body b;
  end Default;

  model Redeclared "der(x) = -3 x^2: x = 1/(1 + 3 t); z = 9*2 + 1; w = 2*2 + 5"
    inner World world(redeclare function field = Square(a = world.g));
    Body b;
    World w2(n = 3);
    Real z = w2.field(2.0);
    Real w = w2.field(2.0, c = 5, k = 2);
  end Redeclared;
end FunctionThroughComponent;
