model MissingAttribute
  Real x(strat = 1);
equation
  x = 1;
end MissingAttribute;
