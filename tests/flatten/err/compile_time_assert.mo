model CompileTimeAssertFails "An assert that fails while a size is evaluated at compile time"
  function n "Number of points for a resolution"
    input Real f;
    output Integer k;
  algorithm
    assert(f > 0, "f > 0 required");
    k := integer(10 / f);
  end n;
  parameter Real f = -1;
  Real x[n(f)] = fill(time, n(f));
end CompileTimeAssertFails;
