// An `inner` component declared after the components whose `outer` reads its parameters
// at compile time (a conditional component's condition, a size): the MSL's MultiBody
// examples declare `inner World world` after the joints whose animation shapes exist
// `if world.enableAnimation`. Inner components are instantiated before the others.
model InnerDeclaredLast
  model W
    parameter Boolean enable = true;
    parameter Integer n = 2;
  end W;
  model B
    outer W world;
    Real x(start = 1, fixed = true);
    Real shown = x if world.enable;
    Real v[world.n] = fill(x, world.n);
  equation
    der(x) = -x;
  end B;
  B b;
  inner W world(n = 3);
end InnerDeclaredLast;
