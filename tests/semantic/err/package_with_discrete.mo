// expect: E2027 @3:20
package P
  discrete Integer n;
end P;
