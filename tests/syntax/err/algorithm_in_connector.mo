connector C
  Real v;
algorithm
  v := 1;
end C;
