// A constant range of 9e9 elements: refused at compile time (at most 10^7), never
// allocated (a mutated model once asked for 41 GB).
model HugeConstantRange
  constant Real c[:] = 1.0:1e-9:10;
  Real x = c[2];
end HugeConstantRange;
