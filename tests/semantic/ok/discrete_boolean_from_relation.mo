// A relation is a discrete-time expression: a Boolean equated to it outside when is fine.
model M
  Real x = sin(time);
  Boolean b;
equation
  b = x > 0;
end M;
