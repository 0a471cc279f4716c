model HeldStateEvents "floor of a state: x = 2.5 sin(time) crosses the integers at asin(k/2.5)"
  Real x(start = 0, fixed = true);
  Real v(start = 2.5, fixed = true);
  Integer n "floor(x)";
  discrete Integer changes(start = 0, fixed = true);
equation
  der(x) = v;
  der(v) = -x;
  n = floor(x);
  when change(n) then
    changes = pre(changes) + 1;
  end when;
  annotation(experiment(StopTime = 6));
end HeldStateEvents;
