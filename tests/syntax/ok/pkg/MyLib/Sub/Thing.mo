within MyLib.Sub;
model Thing "A model stored in its own file inside MyLib/Sub"
  import MyLib.Units.Length;
  import U = MyLib.Units;
  parameter Length L = 1.5 "Length";
  parameter Integer n = defaultSize "Found by lookup in the enclosing package Sub";
  parameter U.Time tau = 2 "Time constant";
  Real x[n](each start = 1, each fixed = true);
equation
  for i in 1:n loop
    tau * der(x[i]) = -x[i] + scale(MyLib.g * L / i, factor = 0.1);
  end for;
end Thing;
