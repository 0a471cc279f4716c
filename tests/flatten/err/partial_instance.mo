model PartialInstance "An instance of a partial class (spec 4.7)"
  partial model Source
    Real y;
  end Source;
  model Constant
    extends Source;
  equation
    y = 1;
  end Constant;
  Constant c "legal: a class that extends the partial one";
  Source s "illegal";
end PartialInstance;
