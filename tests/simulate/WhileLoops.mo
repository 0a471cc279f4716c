// `while` loops whose condition depends on variables, in functions called from
// equations (as the MSL's table search in Blocks.Sources.TimeTable): unrolled with a
// run-time check that the loop ended.
package WhileLoops
  function firstAbove "The index of the first entry above x (the last when none is)"
    input Real x;
    input Real table[:];
    output Integer i;
  algorithm
    i := 1;
    while i < size(table, 1) and table[i] <= x loop
      i := i + 1;
    end while;
  end firstAbove;

  model Search "k = floor(time) + 2 on 0..4, then 6"
    parameter Real table[6] = {0, 1, 2, 3, 4, 5};
    Real k = firstAbove(time, table);
    annotation(experiment(StopTime = 4.5));
  end Search;

  model TooLong "needs more than 64 iterations once 100 time passes 0.64"
    parameter Real table[100] = linspace(0, 1, 100);
    Real k = firstAbove(100 * time, table);
    annotation(experiment(StopTime = 1));
  end TooLong;
end WhileLoops;
