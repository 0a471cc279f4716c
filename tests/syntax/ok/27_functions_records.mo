// Functions with record inputs and outputs, record constructors,
// String results, function annotations (derivative, smoothOrder, Inline)
// and calls from equations, bindings and algorithms.
package ComplexMath "Complex arithmetic with records"
  record Complex "Complex number"
    Real re "Real part";
    Real im "Imaginary part";
  end Complex;

  function cmul "Product of two complex numbers"
    input Complex a;
    input Complex b;
    output Complex c;
  algorithm
    c := Complex(re = a.re * b.re - a.im * b.im, im = a.re * b.im + a.im * b.re);
  end cmul;

  function cabs "Modulus of a complex number"
    input Complex z;
    output Real r;
  algorithm
    r := sqrt(z.re ^ 2 + z.im ^ 2);
    annotation(Inline = true);
  end cabs;

  function cube "Cube with a derivative function"
    input Real x;
    output Real y;
  algorithm
    y := x ^ 3;
    annotation(derivative = cubeDer, smoothOrder = 2);
  end cube;

  function cubeDer "Time derivative of cube"
    input Real x;
    input Real der_x;
    output Real der_y;
  algorithm
    der_y := 3 * x ^ 2 * der_x;
  end cubeDer;

  function describe "Text description of a complex number"
    input Complex z;
    input String unit = "V";
    output String s;
  algorithm
    s := String(z.re, significantDigits = 4) + " + " + String(z.im, significantDigits = 4) + "j " + unit;
  end describe;
end ComplexMath;

model Phasors "Uses the complex functions"
  import ComplexMath.Complex;
  import CM = ComplexMath;
  parameter Complex z0 = Complex(re = 1, im = 0);
  parameter Complex j(re = 0, im = 1) "Record parameter with a modifier";
  parameter String text = CM.describe(z0, unit = "A");
  Complex z "Rotating phasor";
  Real magnitude;
  Real c;
  Real dc;
equation
  z = CM.cmul(Complex(re = cos(time), im = sin(time)), z0);
  magnitude = CM.cabs(CM.cmul(z, j));
  c = CM.cube(time);
  dc = der(c);
end Phasors;
