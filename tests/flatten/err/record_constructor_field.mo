model RecordConstructorField
  record Point
    Real x;
    Real y;
  end Point;
  function origin
    output Point p = Point(0, 0);
  end origin;
  parameter Point a = Point(x = 1, z = 2);
  parameter Point b = origin();
  Point c = Point(1, 2, 3);
end RecordConstructorField;
