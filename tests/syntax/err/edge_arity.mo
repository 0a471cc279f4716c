model A
  Boolean b;
  Boolean c;
equation
  b = time > 1;
  c = edge();
end A;
