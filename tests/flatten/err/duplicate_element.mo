partial model Body
  Real a[3] "acceleration";
equation
  a = zeros(3);
end Body;

model DuplicateElement
  extends Body;
  parameter Real a = 1 "semi-axis";
end DuplicateElement;
