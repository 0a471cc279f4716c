within UnilateralMBS;
package Functions "Quaternion helper functions"
end Functions;
