partial model Base
  Real x;
end Base;

model A
  extends Bsae;
equation
  x = 1;
end A;
