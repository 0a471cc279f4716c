package FunctionOutputSize "A function output sized by an input (`output Real y[n]`), as the MSL's filter design functions"
  function ramp
    input Integer n;
    input Real t;
    output Real y[n];
  algorithm
    for i in 1:n loop
      y[i] := i * t;
    end for;
  end ramp;

  model Use
    parameter Integer n = 3;
    Real y[n];
  equation
    y = ramp(n, time);
  end Use;
end FunctionOutputSize;
