model Inner
  parameter Real k = 1;
end Inner;

model ModifierOfMissingElement
  Inner a(kk = 2);
end ModifierOfMissingElement;
