model PruneKeepsInitialization "The initial value of x comes from a variable that nothing after the start reads"
  Real x(fixed=false);
  Real y "the only requested output";
  Real guess "read only by the initial equation";
equation
  der(x) = -x;
  guess = 2 + cos(time);
  y = x;
initial equation
  x = guess;
end PruneKeepsInitialization;
