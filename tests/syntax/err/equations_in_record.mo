record R
  Real a;
equation
  a = 1;
end R;
