within UnilateralMBS;
package Examples "Scenes of section 4 of the paper, parametrised; models/ sets their data"
end Examples;
