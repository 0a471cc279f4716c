// A protected class used by name inside the package that declares it.
package P
  model Public
    Hidden h;
    Real y = h.x;
  end Public;
protected
  model Hidden
    Real x = 1;
  end Hidden;
end P;
model M
  P.Public p;
end M;
