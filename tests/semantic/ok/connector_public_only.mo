// A connector with parameters, constants and inherited elements, all public.
connector Base
  Real v;
end Base;
connector Pin
  extends Base;
  flow Real i;
  parameter Real r = 1;
end Pin;
