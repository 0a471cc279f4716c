model SettleOffZero "A located crossing whose event leaves its function off zero, on the side it came from, while the flow keeps driving it towards zero: the reinit at the first crossing of y <= 0.5 puts y 1e-11 above the threshold (beyond the relations' rounding noise, 1e-14), so by Modelica semantics the relation is false after that event and true again at a second event when y comes down, 1e-8 s later. The relation must not take the value the flow will give it before its function gets there: held against its operands, that value is a missed crossing at the next step, and again at every event after it (E4006, chattering)"
  Real y(start = 0.501, fixed = true);
  Integer n(start = 0, fixed = true) "the edges of y <= 0.5";
equation
  der(y) = -1e-3;
  when y <= 0.5 then
    n = pre(n) + 1;
    reinit(y, if pre(n) == 0 then 0.5 + 1e-11 else y);
  end when;
  annotation(experiment(StopTime = 2, Interval = 0.01, Tolerance = 1e-6));
end SettleOffZero;
