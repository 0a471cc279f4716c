model SharedValues "Temporaries read outside the instruction that computes them: operands of relations with events and of zero crossings, a held rounding's argument, when conditions and values, a Newton block's residuals, an output computed from a sum that also feeds a derivative"
  Real x(start = 0.3, fixed = true);
  Real v(start = 1, fixed = true);
  Real z(start = 0.5);
  Real q;
  Real w;
  Integer k(start = 0, fixed = true);
  discrete Real last(start = 0, fixed = true);
equation
  der(x) = v;
  der(v) = if x*2 + time > 1.5 then -3*x*x - v + 0.1*z else 2*sin(x) - 0.1*v*z;
  z + 0.2*sin(z) = x*x + 0.1*v;
  q = floor(3*x + v) + mod(time*4 + x, 1.5);
  w = (x*2 + time)*(x*2 + time);
  when x*v > 0.4 then
    k = pre(k) + 1;
    last = x*v + z + q;
  end when;
  annotation(experiment(StopTime = 4, Interval = 0.01));
end SharedValues;
