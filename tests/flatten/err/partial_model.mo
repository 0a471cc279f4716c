partial model PartialModel
  Real x;
equation
  x = 1;
end PartialModel;
