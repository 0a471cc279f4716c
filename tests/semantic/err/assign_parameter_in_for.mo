// expect: E2025 @7:5
model M
  parameter Real p[2] = {1, 2};
  Real x;
algorithm
  for i in 1:2 loop
    p[i] := 0;
  end for;
  x := 1;
end M;
