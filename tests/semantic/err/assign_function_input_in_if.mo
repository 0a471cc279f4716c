// expect: E2026 @7:5
function f
  input Real u;
  output Real y;
algorithm
  if u < 0 then
    u := -u;
  end if;
  y := u;
end f;
