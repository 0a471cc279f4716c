// Import clauses of all three forms, imports in packages, models and
// encapsulated classes, and an empty within clause.
within;

package Geometry "Package used by the import examples"
  constant Real pi = 3.141592653589793;

  package Shapes
    function circleArea
      input Real r;
      output Real a;
    algorithm
      a := pi * r ^ 2;
    end circleArea;

    function squareArea
      input Real side;
      output Real a;
    algorithm
      a := side ^ 2;
    end squareArea;
  end Shapes;

  record Box
    Real w = 1;
    Real h = 1;
  end Box;
end Geometry;

model QualifiedImport "import A.B;"
  import Geometry.Shapes.circleArea;
  Real a = circleArea(2.0);
end QualifiedImport;

model RenamingImport "import X = A.B;"
  import S = Geometry.Shapes;
  import Geometry.Box;
  Real a = S.squareArea(3.0);
  Box b(w = 2);
end RenamingImport;

model UnqualifiedImport "import A.B.*;"
  import Geometry.Shapes.*;
  Real a = circleArea(1.0) + squareArea(1.0);
end UnqualifiedImport;

encapsulated model EncapsulatedUser "Encapsulated classes must import what they use"
  import Geometry;
  import Geometry.Shapes.*;
  Real a = Geometry.pi * 2 + squareArea(0.5);
end EncapsulatedUser;

package Application "Imports are visible in nested classes"
  import Geometry.Shapes.circleArea "Import with a description";
  import G = Geometry;

  model Disk
    parameter Real r = 0.3;
    Real area = circleArea(r);
    Real perimeter = 2 * G.pi * r;
  end Disk;
end Application;
