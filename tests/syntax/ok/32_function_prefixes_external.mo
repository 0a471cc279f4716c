// Function prefixes and external functions (spec 12.3, 12.9).
package ExternalFunctions
  pure function hypot "An ordinary pure function"
    input Real x;
    input Real y;
    output Real r;
  algorithm
    r := sqrt(x * x + y * y);
  end hypot;

  impure function seed "Reads outside state: impure"
    input Integer id;
    output Integer s;
  external "C" s = ModelicaRandom_automaticGlobalSeed(id)
    annotation (Library = "ModelicaExternalC");
  end seed;

  function cosine "Default external call: same name, inputs in order"
    input Real u;
    output Real y;
  external "builtin";
  end cosine;

  function solve "FORTRAN call with an explicit argument list"
    input Real A[:, :];
    input Real b[size(A, 1)];
    output Real x[size(A, 1)] = b;
    output Integer info;
  protected
    Real Awork[size(A, 1), size(A, 2)] = A;
    Integer ipiv[size(A, 1)];
  external "FORTRAN 77" dgesv(size(A, 1), 1, Awork, size(A, 1), ipiv, x, size(A, 1), info)
    annotation (Library = "lapack");
    annotation (Documentation(info = "<html>LAPACK</html>"));
  end solve;

  function noLanguage
    input Real u;
    output Real y;
  external;
  end noLanguage;

  impure function printLine
    input String s;
  external "C" ModelicaInternal_print(s, "") annotation (IncludeDirectory = "modelica://Modelica/Resources/C-Sources");
  end printLine;
end ExternalFunctions;
