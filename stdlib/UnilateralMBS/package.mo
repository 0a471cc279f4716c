within ;
package UnilateralMBS "Multibody systems with unilateral constraints (transcribed from Kossenko, Implementation of Unilateral Multibody Dynamics on Modelica, section 3)"
  import SI = Modelica.SIunits;
  // The paper writes SI.Velocity, SI.Impulse, ...; this import makes the alias visible
  // in every class of the package (lookup goes through the enclosing package's imports).
  annotation (Documentation(info="<html>
<p>Acausal model of unilateral constraints (states Flight = 0, Sliding = 1, Rolling = 2),
impacts with Coulomb friction, regularised friction and time regularisation of landings.
Classes printed in section 3 of paper A are transcribed as closely as possible; classes the
paper only names are reconstructed from shared/spec/contact-models.md, part A, and say so.
See docs/paper-a-transcription.md for every transcription choice.</p>
</html>"));
end UnilateralMBS;
