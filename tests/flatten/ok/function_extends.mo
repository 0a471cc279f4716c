// A function that extends a partial function inherits its inputs and outputs
// (`function quantile extends partialQuantile`, as in Modelica.Math.Distributions).
package Quantiles
  partial function partialQuantile
    input Real u "probability in [0, 1]";
    output Real y "the quantile";
  end partialQuantile;

  function uniform "uniform on [y_min, y_max]"
    extends partialQuantile;
    input Real y_min = 0;
    input Real y_max = 1;
  algorithm
    y := u * (y_max - y_min) + y_min;
  end uniform;
end Quantiles;

model FunctionExtends
  parameter Real q = Quantiles.uniform(0.25, y_min = 2, y_max = 6) "evaluated: 3";
  Real y;
equation
  y = Quantiles.uniform(time, 1, 3);
end FunctionExtends;
