model OperatorTypes "Operators applied to variables of the wrong type (spec 3.7)"
  Integer n(start = 0);
  Real x(start = 1);
  Boolean b;
  Boolean c[2] = {time > 1, time > 2};
  Boolean e "legal: edge of an element of a Boolean array";
equation
  der(x) = -x;
  n = integer(time);
  b = edge(c[1]) "legal: edge of an element of a Boolean array";
  when edge(x) then
    reinit(x, 1);
  end when;
  e = edge(c[2]) and der(n) > 0;
end OperatorTypes;
