// expect: E2029 @12:8
package Lib
  impure function g
    input Real u;
    output Real y = u;
  end g;
end Lib;
pure function f
  input Real u;
  output Real y;
algorithm
  y := Lib.g(u);
end f;
