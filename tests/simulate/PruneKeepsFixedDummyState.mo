model PruneKeepsFixedDummyState "A fixed start on a variable that index reduction made a dummy state, and that no requested output or derivative reads"
  parameter Real s0 = 1;
  parameter Real d = 0.1 "damping";
  Real s(start = 0, fixed = true) "fixed start: the initial equation s = 0";
  Real v(start = 0, fixed = true);
  Real s_rel(start = 0, stateSelect = StateSelect.prefer) "the state chosen; its start is only a guess";
  Real v_rel;
equation
  s_rel = s0 - s;
  v_rel = der(s_rel);
  der(s) = v;
  der(v) = s_rel - 1.5 + d * v_rel;
end PruneKeepsFixedDummyState;
