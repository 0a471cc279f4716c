// Discrete variables at event instants, as the MSL's noise blocks use them: `pre` of an
// Integer array set by initial equations, two `when` clauses on one condition where one
// reads what the other assigns at the same instant, and an Integer parameter solved by
// initialization from a large value.
package DiscreteInstants
  model Fibonacci "s steps through the Fibonacci numbers at 0, 0.1, 0.2, ...; r lags one step"
    Integer s[2];
    discrete Real r;
    discrete Real twice "2 s[2], from the other clause at the same instant";
  initial equation
    pre(s) = {3, 4};
    r = pre(s[1]);
    twice = 2 * s[2];
  equation
    when sample(0, 0.1) then
      twice = 2 * s[2];
    end when;
    when sample(0, 0.1) then
      s = {pre(s[2]), pre(s[1]) + pre(s[2])};
      r = pre(s[1]);
    end when;
    annotation(experiment(StopTime = 0.25));
  end Fibonacci;

  model LargeSeed "seed (fixed = false) from a value whose rounding exceeds a plain difference step"
    parameter Integer fixedSeed = 67867967;
    final parameter Integer seed(fixed = false);
    parameter Real k(fixed = false);
    Real x(start = 1, fixed = true);
  initial equation
    seed = fixedSeed;
    k = 2 * seed;
  equation
    der(x) = -x + k * 1e-9;
    annotation(experiment(StopTime = 1));
  end LargeSeed;
end DiscreteInstants;
