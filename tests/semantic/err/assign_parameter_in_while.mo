// expect: E2025 @8:5
model M
  parameter Integer n = 3;
  Real x;
algorithm
  x := 0;
  while n > 0 loop
    n := n - 1;
  end while;
end M;
