// if / elseif / else equations with continuous and parameter conditions,
// if-equations containing for-equations, and nested if-equations.
model Saturation "Piecewise-defined output"
  parameter Real uMax = 1;
  parameter Real uMin = -uMax;
  Real u = 2 * sin(time);
  Real y;
equation
  if u > uMax then
    y = uMax;
  elseif u < uMin then
    y = uMin;
  else
    y = u;
  end if;
end Saturation;

model ParameterSwitch "Structure selected by parameters"
  parameter Boolean useLinear = true;
  parameter Integer order = 2;
  Real x(start = 1, fixed = true);
  Real f;
  Real g;
equation
  if useLinear then
    f = -x;
  else
    f = -x ^ 3;
  end if;
  der(x) = f;
  if order == 1 then
    g = x;
  elseif order == 2 then
    if useLinear then
      g = x ^ 2;
    else
      g = x ^ 2 + f;
    end if;
  else
    g = 0;
  end if;
end ParameterSwitch;

model ArrayFill "for-equations inside an if-equation"
  parameter Integer n = 3;
  parameter Boolean reverse = false;
  Real w[n];
equation
  if reverse then
    for i in 1:n loop
      w[i] = n - i + 1;
    end for;
  else
    for i in 1:n loop
      w[i] = i * time;
    end for;
  end if;
end ArrayFill;
