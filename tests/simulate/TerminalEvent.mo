model TerminalEvent "when terminal() fires once, at the stop time, after the last sample instant"
  Real x(start = 1, fixed = true);
  discrete Real atEnd(start = 0, fixed = true);
  discrete Integer n(start = 0, fixed = true);
equation
  der(x) = -x;
  when terminal() then
    atEnd = x;
  end when;
  when sample(0, 0.25) then
    n = pre(n) + 1;
  end when;
end TerminalEvent;
