// A function with record inputs, outputs and locals.
record R
  Real x;
end R;
function f
  input R r;
  output R s;
protected
  R t;
algorithm
  t := r;
  s := t;
end f;
