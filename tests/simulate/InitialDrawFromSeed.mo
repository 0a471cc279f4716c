// A discrete value the initial equations draw from a free parameter (a noise block's
// first sample from its seed), read by the initial equation of a state: the finite
// differences over the parameter must not leave a draw from a perturbed seed behind.
model InitialDrawFromSeed
  parameter Real seed(fixed = false, start = 1);
  discrete Real r;
  Real x(start = 0);
  Real y;
initial equation
  seed = 7;
  r = sin(seed * 1e9);
  y = 0;
equation
  y = x + r;
  der(x) = -x;
  when time > 0.5 then
    r = pre(r) + 1;
  end when;
end InitialDrawFromSeed;
