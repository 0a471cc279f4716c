model CompileTimeAssert "A function with an assert, evaluated at compile time for a size"
  function n "Number of points for a resolution"
    input Real f;
    output Integer k;
  algorithm
    assert(f > 0, "f > 0 required");
    k := integer(10 / f);
  end n;
  parameter Real f = 2;
  Real x[n(f)] = fill(time, n(f));
end CompileTimeAssert;
