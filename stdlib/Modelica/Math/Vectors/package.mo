within Modelica.Math;
package Vectors "Library of functions operating on vectors"
end Vectors;
