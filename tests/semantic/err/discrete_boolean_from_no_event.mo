// expect: E2033 @7:15
// A relation inside noEvent is not discrete-time: a Boolean cannot be given it.
model M
  Real x = sin(time);
  Boolean b;
equation
  b = noEvent(x > 0);
end M;
