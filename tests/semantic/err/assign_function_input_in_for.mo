// expect: E2026 @7:5
function f
  input Real u[3];
  output Real y = 0;
algorithm
  for i in 1:3 loop
    u[i] := 2*u[i];
  end for;
end f;
