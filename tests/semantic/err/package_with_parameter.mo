// expect: E2027 @3:18
package P
  parameter Real k = 1;
end P;
