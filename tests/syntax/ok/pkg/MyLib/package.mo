within;
package MyLib "Example library stored as a package folder"
  import SI = MyLib.Units;

  package Units "Types with units"
    type Length = Real(unit = "m");
    type Time = Real(unit = "s");
  end Units;

  constant Real g = 9.81 "Gravity acceleration";

  model Example "Uses a model from the sub-package folder"
    Sub.Thing thing(L = 2.0);
    SI.Length total = sum(thing.x) * thing.L;
  end Example;

  annotation(version = "1.0.0",
    Documentation(info = "<html><p>Package folder example with a sub-package folder.</p></html>"));
end MyLib;
