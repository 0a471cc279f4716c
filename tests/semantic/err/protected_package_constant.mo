// expect: E2022 @8:14
package P
  constant Real a = 1;
protected
  constant Real c = 2;
end P;
model M
  Real y = P.c;
end M;
