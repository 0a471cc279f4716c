model ConditionalExits "return and break under conditions that depend on variables, in inlined functions"
  function firstAbove "index of the first element above a limit (0: none): return in a loop"
    input Real x[:];
    input Real limit;
    output Integer k;
  algorithm
    k := 0;
    for i in 1:size(x, 1) loop
      if x[i] > limit then
        k := i;
        return;
      end if;
    end for;
  end firstAbove;
  function clippedSum "break out of a loop"
    input Real x[:];
    input Real cap;
    output Real s;
  algorithm
    s := 0;
    for i in 1:size(x, 1) loop
      s := s + x[i];
      if s > cap then
        s := cap;
        break;
      end if;
    end for;
  end clippedSum;
  function sign3 "early returns"
    input Real x;
    output Real y;
  algorithm
    if x > 1 then
      y := 1;
      return;
    elseif x < -1 then
      y := -1;
      return;
    end if;
    y := x;
  end sign3;
  Real v[3] = {sin(time), sin(2*time), sin(3*time)};
  Integer k = firstAbove(v, 0.5);
  Real s = clippedSum({time, 2*time, 3*time}, 3);
  Real y = sign3(4*time - 2);
end ConditionalExits;
