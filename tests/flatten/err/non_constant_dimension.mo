model NonConstantDimension
  Real n = time;
  Real x[n];
end NonConstantDimension;
