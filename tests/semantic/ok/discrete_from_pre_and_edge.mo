// pre, edge and change are discrete-time: fine outside when.
model M
  Boolean b = time > 0.5;
  Boolean rising = edge(b);
  Boolean changed = change(b);
  Boolean previous = pre(b);
end M;
