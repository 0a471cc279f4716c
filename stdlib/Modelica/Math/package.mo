within Modelica;
package Math "Library of mathematical functions (e.g., sin, cos) and of functions operating on vectors and matrices"
  // sin, cos, exp, ... are the built-in functions of the language and are not repeated here.
end Math;
