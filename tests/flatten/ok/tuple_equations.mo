// `(r, state) = f(pre(state))` counts one equation per scalar of each target: here
// 1 + 3 (the MSL's noise generators write their random number and state this way).
package TupleLib
  function step "a counter with a 3-element state"
    input Integer s[3];
    output Real r;
    output Integer next[3];
  algorithm
    next := {s[2], s[3], s[1] + s[2]};
    r := next[3] / 10;
  end step;
end TupleLib;

model TupleEquations
  discrete Real r(start = 0);
  discrete Integer state[3](start = {1, 1, 2});
equation
  when sample(0, 0.1) then
    (r, state) = TupleLib.step(pre(state));
  end when;
end TupleEquations;
