// expect: E2027 @3:8
package P
  Real x;
end P;
