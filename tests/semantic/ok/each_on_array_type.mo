// `each` on a component of an array type (`type Vector = Real[3]`).
type Vector = Real[3];
model M
  Vector v(each start = 0, each fixed = true);
equation
  der(v) = {1, 1, 1};
end M;
