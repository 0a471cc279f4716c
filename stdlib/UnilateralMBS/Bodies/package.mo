within UnilateralMBS;
package Bodies "Rigid bodies able to process impacts (section 3.2 of the paper)"
end Bodies;
