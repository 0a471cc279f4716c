model NoVisual "A model without any drawn component"
  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
end NoVisual;
