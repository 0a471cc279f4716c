// A protected constant read through the full path from inside its package.
package P
  model Use
    Real y = P.c;
  end Use;
protected
  constant Real c = 3;
end P;
model M
  P.Use u;
end M;
