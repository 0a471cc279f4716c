// expect: E2027 @3:14
package P
  input Real u;
end P;
