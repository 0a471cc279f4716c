// Two equations for x, none for y: structurally singular though the counts agree.
model Singular
  Real x, y;
equation
  x = 1;
  2*x = 2 + 0*time;
end Singular;
