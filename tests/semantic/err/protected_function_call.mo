// expect: E2022 @10:14
package P
protected
  function f
    input Real u;
    output Real y = 2*u;
  end f;
end P;
model M
  Real y = P.f(1);
end M;
