model ComponentArrayReductions "comprehensions and reductions that select components by the iterator"
  model Coil
    Real r[3];
  equation
    der(r) = {1, 2, 3};
  end Coil;
  parameter Integer n = 3;
  Coil coil[n];
  Real z[n] = {coil[i].r[3] for i in 1:n};
  Real s = sum(coil[i].r[1] for i in 1:n);
  Real m = max(coil[i].r[2] * i for i in 1:n);
end ComponentArrayReductions;
