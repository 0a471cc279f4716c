// `[:]` takes its size from the binding's shape when its value is not known at
// compile time (`reset = {stop.on}`: a variable, of a component declared below).
package ColonShape
  block Button
    input Boolean reset[:] = {false};
    output Boolean on;
  equation
    on = not reset[1] and time > 0.5;
  end Button;
end ColonShape;

model ColonSizeFromShape
  ColonShape.Button start(reset = {stop.on});
  ColonShape.Button stop(reset = {start.on, false});
end ColonSizeFromShape;
