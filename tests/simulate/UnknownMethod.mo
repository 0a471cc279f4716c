model UnknownMethod "An experiment annotation naming no method unimo has"
  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
  annotation (experiment(StopTime = 1, __unimo_method = "dassl"));
end UnknownMethod;
