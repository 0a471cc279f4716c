within Modelica.Blocks;
package Interfaces "Library of connectors and partial models for input/output blocks"
end Interfaces;
