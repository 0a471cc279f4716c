type Mode = enumeration(Off, Low, High);

model Enumerations
  parameter Mode initial_mode = Mode.Low;
  discrete Mode mode(start = Mode.Off);
  Real x(start = 0, fixed = true);
equation
  der(x) = if mode == Mode.High then 2 else if mode == Mode.Low then 1 else 0;
  when x > 1 then
    mode = Mode.High;
  end when;
end Enumerations;
