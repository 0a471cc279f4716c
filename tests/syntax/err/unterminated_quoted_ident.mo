model A
  Real 'my var;
end A;
