// A class that contains a component of its own type, twice: without a condition to
// stop it the instances would multiply without end.
model Node
  Real x;
  Node left;
  Node right;
end Node;

model RecursiveClass
  Node root;
end RecursiveClass;
