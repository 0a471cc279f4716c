// Class extensions (spec 7.3.2) and derivative classes (spec 12.7.2).
package ClassExtension
  partial package Base
    replaceable partial model Part
      parameter Real k = 1;
      Real y;
    end Part;

    replaceable function f
      input Real x;
      input Real a;
      output Real y;
    algorithm
      y := a * x ^ 2;
    end f;

    type Dfdx = der(f, x) "df/dx";
    type Dfdxa = der(f, x, a);
  end Base;

  package Specific
    extends Base;

    redeclare model extends Part(k = 2) "Part with an equation"
    equation
      y = k * time;
    end Part;

    redeclare function extends f "Adds nothing but a description"
    end f;
  end Specific;
end ClassExtension;
