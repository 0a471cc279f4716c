within MyLib;
package Sub "Sub-package stored in its own directory"
  constant Integer defaultSize = 3 "Default number of states";

  function scale "Scales a value"
    input Real x;
    input Real factor = 2;
    output Real y;
  algorithm
    y := factor * x;
  end scale;
end Sub;
