// A protected function called from inside its package.
package P
  function f
    input Real u;
    output Real y = g(u);
  end f;
protected
  function g
    input Real u;
    output Real y = 3*u;
  end g;
end P;
model M
  Real y = P.f(1);
end M;
