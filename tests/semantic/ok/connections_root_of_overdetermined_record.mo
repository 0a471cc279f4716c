// Connections operators on a record with an equalityConstraint function (an alias of it too).
record Reference
  Real theta;
  function equalityConstraint
    input Reference r1;
    input Reference r2;
    output Real residue[0];
  algorithm
  end equalityConstraint;
end Reference;
record Reference2 = Reference;
connector Pin
  Real v;
  flow Real i;
  Reference reference;
  Reference2 other;
end Pin;
model M
  Pin p;
equation
  Connections.root(p.reference);
  Connections.root(p.other);
  p.v = 1;
  p.reference.theta = 0;
  p.other.theta = 0;
end M;
