// A type name that denotes nothing, inside a class the model only uses (a record of a
// parameter, the class of a component): reported where it is written.
record Data
  Real m = 1;
  eal k = 2;
end Data;

model Part
  Rael x;
end Part;

model UnknownTypeInUsedClass
  parameter Data d;
  Part p;
  Real y = d.m;
end UnknownTypeInUsedClass;
