// expect: E2025 @7:5
model M
  parameter Real p = 1;
  Real x;
algorithm
  if time > 1 then
    p := 2;
  end if;
  x := 1;
end M;
