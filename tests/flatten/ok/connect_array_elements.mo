// Connections to elements of connector arrays (`connect(a.y, s.u[2])`, spec 9.1):
// a variable connected by element somewhere is connected element by element
// everywhere, also where the whole array is connected.
package ArrayElements
  connector RealInput = input Real;
  connector RealOutput = output Real;

  block Sum
    parameter Integer nin = 2;
    RealInput u[nin];
    RealOutput y;
  equation
    y = sum(u);
  end Sum;

  block Ramp
    parameter Real k = 1;
    RealOutput y;
  equation
    y = k * time;
  end Ramp;

  block Ramps
    RealOutput y[3];
  equation
    y = {1, 2, 3} * time;
  end Ramps;
end ArrayElements;

model ConnectArrayElements
  ArrayElements.Sum s(nin = 3);
  ArrayElements.Sum copy(nin = 3);
  ArrayElements.Ramp a(k = 1), b(k = 2), c(k = 3);
  ArrayElements.Ramps r;
  ArrayElements.Sum whole(nin = 3);
equation
  connect(a.y, s.u[1]);
  connect(b.y, s.u[2]);
  connect(c.y, s.u[3]);
  connect(s.u, copy.u);
  connect(r.y, whole.u);
end ConnectArrayElements;
