within;
package Modelica "Modelica Standard Library: the subset shipped with unimo (see docs/stdlib.md)"
  // Only the classes that the bundled models and libraries use are present.
  // Every definition follows the Modelica Standard Library (MSL); docs/stdlib.md
  // names the MSL version of each one.
end Modelica;
