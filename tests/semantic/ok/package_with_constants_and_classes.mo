// A package holds constants and classes.
package P
  constant Real g = 9.81;
  constant Integer n = 3;
  type Length = Real(unit = "m");
  model A
    Length h = g;
  end A;
end P;
model M
  P.A a;
end M;
