// expect: E2022 @9:16
package P
  package Q
  protected
    constant Real c = 3;
  end Q;
end P;
model M
  Real y = P.Q.c;
end M;
