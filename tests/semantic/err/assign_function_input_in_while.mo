// expect: E2026 @8:5
function f
  input Integer n;
  output Integer y = 0;
algorithm
  while n > 0 loop
    y := y + 1;
    n := n - 1;
  end while;
end f;
