within;
package Unimo "Components backed by unimo's runtime (external objects)"
  function invariant "Declares g = 0 an invariant of the solution: the simulator projects the states onto it after each step and event (inside an if-equation branch: while that branch is taken)"
    input Real g "Stays 0";
    external "builtin";
  end invariant;
end Unimo;
