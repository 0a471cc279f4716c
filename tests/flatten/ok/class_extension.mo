// A class extension `redeclare model extends Part(...)` (spec 7.3.2) adds to the
// inherited replaceable class and modifies it; a use site modifies it once more.
package ClassExtensionLib
  partial package Base
    replaceable partial model Part
      parameter Real k = 1;
      parameter Real m = 3;
      Real y;
    end Part;
  end Base;

  package Specific
    extends Base;
    redeclare model extends Part(k = 2)
      Real z;
    equation
      y = k * time;
      z = m * y;
    end Part;
  end Specific;
end ClassExtensionLib;

model ClassExtension
  ClassExtensionLib.Specific.Part p(m = 5);
end ClassExtension;
