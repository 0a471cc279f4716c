model Sub
  Real z(start = 0, fixed = true);
equation
  der(z) = 1;
end Sub;

model ConditionalComponents
  parameter Boolean useSub = false;
  parameter Boolean useOther = true;
  Sub present if useOther;
  Sub absent if useSub;
end ConditionalComponents;
