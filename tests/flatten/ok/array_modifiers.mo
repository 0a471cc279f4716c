model ArrayModifiers "modifiers of component arrays split per element, also when not constant"
  model M
    parameter Real k;
    input Real u;
    Real x(start = 1, fixed = true);
  equation
    der(x) = -k * x + u;
  end M;
  parameter Integer n = 3;
  parameter Real ks[n] = {1, 2, 3};
  Real us[n] = {time, 2 * time, 3 * time};
  M m[n](k = 2 * ks, u = us + ones(n));
  M p[n](k = ks, u = -sin(us) .* ks);
end ArrayModifiers;
