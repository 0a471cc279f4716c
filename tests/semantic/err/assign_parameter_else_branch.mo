// expect: E2025 @10:5
model M
  parameter Real p = 1;
  Real x;
algorithm
  if time > 1 then
    x := 1;
  else
    x := 2;
    p := 3;
  end if;
end M;
