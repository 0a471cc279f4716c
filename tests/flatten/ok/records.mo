package RecordLib "records for the records test"
  record Complex "a complex number"
    Real re;
    Real im;
  end Complex;

  record Point
    Real x;
    Real y;
  end Point;

  record Setting "a field default that the constructor uses"
    Real k = 2;
    Real offset;
  end Setting;

  record Frame "nested records and an array field"
    Point origin;
    Real axis[2];
  end Frame;

  record Material
    parameter Real density = 1000;
  end Material;

  record Steel "inherited fields come first"
    extends Material(density = 7850);
    Real yieldStress;
  end Steel;

  function cmul
    input Complex a;
    input Complex b;
    output Complex c;
  algorithm
    c := Complex(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
  end cmul;

  function scale "a record local and assignment to fields"
    input Frame f;
    input Real k;
    output Frame g;
  protected
    Point p;
  algorithm
    p.x := k * f.origin.x;
    p.y := k * f.origin.y;
    g := Frame(origin = p, axis = f.axis);
    g.axis[1] := k * f.axis[1];
  end scale;

  function norm2
    input Complex z;
    output Real r = sqrt(z.re ^ 2 + z.im ^ 2);
  end norm2;
end RecordLib;

model Records "records as structured variables"
  import RecordLib.*;
  parameter Complex p = Complex(1, 2);
  parameter Complex q = p "bound to another record";
  parameter Point a = Point(y = 4, x = 3) "named arguments";
  parameter Setting st = Setting(offset = 1) "default k";
  parameter Steel s = Steel(yieldStress = 2.5e8);
  parameter Complex roots[2] = {Complex(1, 0), Complex(0, 1)};
  Complex z(re(start = 1, fixed = true), im(start = 0, fixed = true));
  Complex w "a record equation with a function";
  Frame f = Frame(Point(time, 2 * time), {1, 2});
  Frame g;
  Real r;
equation
  der(z.re) = -q.re * z.re + q.im * z.im;
  der(z.im) = -q.im * z.re - q.re * z.im;
  w = cmul(z, roots[2]);
  g = scale(f, a.x);
  r = norm2(w) + s.density - 7850 + 0 * s.yieldStress + norm2(Complex(3, 4)) * st.k + st.offset;
end Records;
