// A call statement whose function reaches an external function unimo does not provide
// (writing a file, as the MSL's realFFTwriteToFile does through ModelicaIO): not
// executed, and said so (W3001); the run goes on. A call of a pure function with its
// outputs unused is dropped without a word.
model UnexecutedCall
  function writeValue "Writes x to a file"
    input String fileName;
    input Real x;
    output Boolean ok;
  external "C" ok = myWriteValue(fileName, x);
  end writeValue;

  function report "Calls writeValue, its result unused by the caller"
    input Real x;
    output Boolean ok;
  algorithm
    ok := writeValue("x.txt", x);
  end report;

  function twice
    input Real x;
    output Real y;
  algorithm
    y := 2*x;
  end twice;

  Real x(start = 1, fixed = true);
equation
  der(x) = -x;
algorithm
  when terminal() then
    report(x);
    twice(x);
  end when;
end UnexecutedCall;
