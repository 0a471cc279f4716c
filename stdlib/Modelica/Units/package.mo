within Modelica;
package Units "Library of type and unit definitions (MSL 4.0 Modelica.Units, subset)"
end Units;
