// Importing a public class of a package with a protected one beside it.
package P
  function f
    input Real u;
    output Real y = 2*u;
  end f;
protected
  function g
    input Real u;
    output Real y = 3*u;
  end g;
end P;
model M
  import P.f;
  Real y = f(1);
end M;
