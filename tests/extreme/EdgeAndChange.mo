model EdgeAndChange "edge and change of a Boolean that follows sin(2 pi (t - 1/4)) > 0"
  Boolean up;
  Boolean down;
  discrete Integer rises(start = 0, fixed = true);
  discrete Integer falls(start = 0, fixed = true);
  discrete Integer switches(start = 0, fixed = true);
equation
  up = sin(2*3.141592653589793*(time - 0.25)) > 0;
  down = not up;
  when edge(up) then
    rises = pre(rises) + 1;
  end when;
  when edge(down) then
    falls = pre(falls) + 1;
  end when;
  when change(up) then
    switches = pre(switches) + 1;
  end when;
  annotation(experiment(StopTime = 2));
end EdgeAndChange;
