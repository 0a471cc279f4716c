within UnilateralMBS;
package Interfaces "Connectors and types (section 3.1 of the paper)"
  annotation (Documentation(info="<html>
<p>Connector convention. The paper's connectors pair a kinematic port (body to constraint)
with a wrench port (constraint to body), as in the author's earlier library. Both carry only
potential (non-flow) variables: a force F on a WrenchPort is the force acting on the body
the port leads to, so a flow variable (whose sign flips across a connection) would
contradict equations such as <code>F = InPort1.F + F1</code> and
<code>Forcen = OutPortA.F*normA</code>. The causality is therefore expressed with
<code>input</code>/<code>output</code> prefixes on the connector components: a body's
kinematic port is an output and its wrench port an input; a constraint's kinematic ports
are inputs and its wrench ports outputs. All vectors are resolved in the absolute frame AF.</p>
</html>"));
end Interfaces;
