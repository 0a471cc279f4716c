package Q
  type State = enumeration(Flight, Sliding, Rolling);
  function twice
    input Real u;
    output Real y;
  algorithm
    y := 2 * u;
  end twice;
  model M
    State s(start = State.Flight);
    Real x(start = 1);
    Real n = Modelica.Math.Vectors.norm({x, 2 * x});
  equation
    der(x) = twice(-x) + sum(x for i in 1:3);
    when x < 0.5 then
      s = State.Sliding;
    end when;
  end M;
end Q;
