// Operator records and overloaded operators (spec 14).
operator record Cplx "A complex number"
  Real re "Real part";
  Real im "Imaginary part";

  encapsulated operator 'constructor'
    function fromReal
      import Cplx;
      input Real re;
      input Real im = 0;
      output Cplx result(re = re, im = im);
    algorithm
      annotation (Inline = true);
    end fromReal;
  end 'constructor';

  encapsulated operator function '+'
    import Cplx;
    input Cplx a;
    input Cplx b;
    output Cplx c "= a + b";
  algorithm
    c := Cplx(a.re + b.re, a.im + b.im);
    annotation (Inline = true);
  end '+';

  encapsulated operator '-'
    function negate
      import Cplx;
      input Cplx a;
      output Cplx c;
    algorithm
      c := Cplx(-a.re, -a.im);
    end negate;

    function subtract
      import Cplx;
      input Cplx a;
      input Cplx b;
      output Cplx c;
    algorithm
      c := Cplx(a.re - b.re, a.im - b.im);
    end subtract;
  end '-';

  encapsulated pure operator function '*'
    import Cplx;
    input Cplx a;
    input Cplx b;
    output Cplx c;
  algorithm
    c := Cplx(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
  end '*';
end Cplx;
