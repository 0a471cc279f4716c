model A
  Real loop;
end A;
