// Algorithm sections: assignments, tuple assignment, if/elseif/else,
// for, while, break, when/elsewhen statements and call statements.
function sinCos "Returns sine and cosine"
  input Real phi;
  output Real s;
  output Real c;
algorithm
  s := sin(phi);
  c := cos(phi);
end sinCos;

model AlgorithmDemo
  parameter Integer n = 5;
  Real x(start = 1, fixed = true);
  Real y;
  Real s;
  Integer k;
  Real a;
  Real b;
  discrete Real sampled(start = 0, fixed = true);
  discrete Integer ticks(start = 0, fixed = true);
equation
  der(x) = -0.5 * x;
algorithm
  y := 2 * x;
  if y > 1.5 then
    s := 1;
  elseif y > 0.5 then
    s := 0.5;
  else
    s := 0;
  end if;
  for i in 1:n loop
    s := s + i * 0.1;
    if i > 3 then
      break;
    end if;
  end for;
  k := 0;
  while k < 3 loop
    k := k + 1;
  end while;
  (a, b) := sinCos(x);
  assert(a <= 1, "sine out of range");
algorithm
  when sample(0, 0.1) then
    sampled := x;
    ticks := pre(ticks) + 1;
  elsewhen x < 0.2 then
    sampled := 0;
    ticks := 0;
  end when;
end AlgorithmDemo;

model NestedLoops "Nested for and while loops in an algorithm"
  parameter Integer n = 4;
  Real A[n, n];
  Real trace;
  Integer steps;
algorithm
  for i in 1:n loop
    for j in 1:n loop
      A[i, j] := if i == j then time else 1 / (i + j - 1);
    end for;
  end for;
  trace := 0;
  for i in 1:n loop
    trace := trace + A[i, i];
  end for;
  steps := 0;
  while true loop
    steps := steps + 1;
    if steps >= n then
      break;
    end if;
  end while;
end NestedLoops;
