model Tank
  Real h;
equation
  der(h) = -h;
end Tnak;
