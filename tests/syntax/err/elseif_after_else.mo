model A
  Real x;
equation
  if time > 1 then
    x = 1;
  else
    x = 2;
  elseif time > 2 then
    x = 3;
  end if;
end A;
