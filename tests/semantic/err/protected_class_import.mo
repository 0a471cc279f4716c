// expect: E2022 @10:12
package P
protected
  function f
    input Real u;
    output Real y = 2*u;
  end f;
end P;
model M
  import P.f;
  Real y = 1;
end M;
