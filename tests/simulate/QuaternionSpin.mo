model QuaternionSpin
  "a body spinning about x at 1 rad/s in quaternions, as MultiBody's Body writes them: all four
   components stateSelect = avoid and the unit-norm constraint; Q = {sin(t/2), 0, 0, cos(t/2)},
   so each static choice of three states is singular at some instant (Q[4] = 0 at t = pi,
   Q[1] = 0 at t = 2 pi)"
  Real Q[4](start = {0, 0, 0, 1}, fixed = {true, true, true, false},
    each stateSelect = StateSelect.avoid);
  Real w[3];
equation
  0 = Q*Q - 1;
  w = 2*{Q[4]*der(Q[1]) + Q[3]*der(Q[2]) - Q[2]*der(Q[3]) - Q[1]*der(Q[4]),
        -Q[3]*der(Q[1]) + Q[4]*der(Q[2]) + Q[1]*der(Q[3]) - Q[2]*der(Q[4]),
         Q[2]*der(Q[1]) - Q[1]*der(Q[2]) + Q[4]*der(Q[3]) - Q[3]*der(Q[4])};
  w = {1, 0, 0};
end QuaternionSpin;
