within UnilateralMBS;
package Constraints "Unilateral constraints between two bodies A and B (section 3.3 of the paper)"
end Constraints;
