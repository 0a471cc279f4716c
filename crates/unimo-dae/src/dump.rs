//! The text dump of the hybrid DAE (`unimo emit --stage dae`), snapshot-tested.

use crate::dae::*;
use crate::events::zero_crossings;
use crate::expr::fmt_num;
use std::fmt::Write;
use unimo_source::Span;

/// Dumps `dae`; `origin` turns a span into `file:line` (or returns an empty string).
pub fn dump(dae: &Dae, origin: &dyn Fn(Span) -> String) -> String {
    let mut o = String::new();
    let show = |e| dae.show(e);
    let _ = writeln!(o, "dae {}", dae.name);
    let groups = [
        ("constants", ScalarKind::Constant),
        ("parameters", ScalarKind::Parameter),
        ("continuous", ScalarKind::Continuous),
        ("derivatives", ScalarKind::Derivative),
        ("discretes", ScalarKind::Discrete),
    ];
    for (title, kind) in groups {
        let members: Vec<&Scalar> = dae
            .scalars
            .iter()
            .filter(|s| s.kind == kind && s.alias.is_none())
            .collect();
        if members.is_empty() {
            continue;
        }
        let _ = writeln!(o, "{title}: {}", members.len());
        for s in members {
            let line = scalar_line(dae, s);
            let _ = writeln!(o, "{line}");
        }
    }
    let aliases: Vec<&Scalar> = dae.scalars.iter().filter(|s| s.alias.is_some()).collect();
    if !aliases.is_empty() {
        let _ = writeln!(o, "aliases: {}", aliases.len());
        for s in aliases {
            let _ = writeln!(o, "  {} = {}", s.name, show(s.alias.expect("filtered")));
        }
    }
    let eqs = |o: &mut String, title: &str, list: &[Equation]| {
        if list.is_empty() {
            return;
        }
        let _ = writeln!(o, "{title}: {}", list.len());
        for (k, e) in list.iter().enumerate() {
            let at = origin(e.origin);
            let sep = if at.is_empty() { "" } else { "  // " };
            let _ = writeln!(o, "  e{k}: {} = {}{sep}{at}", show(e.lhs), show(e.rhs));
        }
    };
    eqs(&mut o, "equations", &dae.equations);
    eqs(&mut o, "initial equations", &dae.initial_equations);
    write_whens(&mut o, dae);
    if !dae.assertions.is_empty() {
        let _ = writeln!(o, "assertions: {}", dae.assertions.len());
        for a in &dae.assertions {
            let _ = writeln!(o, "  assert({}, {:?})", show(a.condition), a.message);
        }
    }
    if !dae.invariants.is_empty() {
        let _ = writeln!(o, "invariants: {}", dae.invariants.len());
        for i in &dae.invariants {
            let _ = writeln!(o, "  0 = {} when {}", show(i.value), show(i.active));
        }
    }
    if !dae.delays.is_empty() {
        let _ = writeln!(o, "delays: {}", dae.delays.len());
        for (k, d) in dae.delays.iter().enumerate() {
            let _ = writeln!(o, "  {k}: records {}", show(d.input));
        }
    }
    let zc = zero_crossings(dae);
    if !zc.relations.is_empty() || !zc.samples.is_empty() {
        let _ = writeln!(
            o,
            "zero crossings: {}",
            zc.relations.len() + zc.samples.len()
        );
        for (k, &z) in zc.relations.iter().chain(&zc.samples).enumerate() {
            let _ = writeln!(o, "  z{k}: {}", show(z));
        }
    }
    if !zc.held.is_empty() {
        let _ = writeln!(o, "held between events: {}", zc.held.len());
        for (k, &h) in zc.held.iter().enumerate() {
            let _ = writeln!(o, "  h{k}: {}", show(h));
        }
    }
    let ex = &dae.experiment;
    if *ex != Experiment::default() {
        let f = |x: Option<f64>| x.map(fmt_num).unwrap_or_else(|| "-".into());
        let _ = writeln!(
            o,
            "experiment: start {} stop {} tolerance {} interval {}",
            f(ex.start_time),
            f(ex.stop_time),
            f(ex.tolerance),
            f(ex.interval)
        );
        if let Some(m) = &ex.method {
            let _ = writeln!(o, "experiment method: {m}");
        }
    }
    o
}

/// One scalar of the dump: its name, type (when not Real), binding and attributes.
fn scalar_line(dae: &Dae, s: &Scalar) -> String {
    let show = |e| dae.show(e);
    let mut line = format!("  {}", s.name);
    match s.ty {
        ScalarType::Real => {}
        ScalarType::Integer => line.push_str(" : Integer"),
        ScalarType::Boolean => line.push_str(" : Boolean"),
        ScalarType::Enumeration(k) => {
            // Predefined enumerations (StateSelect, AssertionLevel) have no entry.
            let name = dae
                .enumerations
                .get(k as usize)
                .map_or("enumeration", |e| &e.0);
            let _ = write!(line, " : {name}");
        }
    }
    if let Some(b) = s.binding {
        let _ = write!(line, " = {}", show(b));
    }
    let mut attrs = Vec::new();
    if let Some(x) = s.start {
        attrs.push(format!("start = {}", show(x)));
    }
    if let Some(f) = s.fixed {
        attrs.push(format!("fixed = {f}"));
    }
    if let Some(x) = s.nominal {
        attrs.push(format!("nominal = {}", show(x)));
    }
    if s.state_select != StateSelect::Default {
        attrs.push(format!("stateSelect = {:?}", s.state_select));
    }
    if s.input {
        attrs.push("input".into());
    }
    if !attrs.is_empty() {
        let _ = write!(line, " ({})", attrs.join(", "));
    }
    line
}

/// The `when` clauses of the dump, each branch with its conditions and actions.
fn write_whens(o: &mut String, dae: &Dae) {
    let show = |e| dae.show(e);
    if !dae.whens.is_empty() {
        let _ = writeln!(o, "when: {}", dae.whens.len());
        for (k, w) in dae.whens.iter().enumerate() {
            for (j, b) in w.branches.iter().enumerate() {
                let conds: Vec<String> = b.conditions.iter().map(|&c| show(c)).collect();
                let kw = if j == 0 { "when" } else { "elsewhen" };
                let _ = writeln!(o, "  w{k}: {kw} {}", conds.join(", "));
                for (a, _) in &b.actions {
                    let text = match a {
                        WhenAction::Assign { target, value } => {
                            format!("{} := {}", dae.name(*target), show(*value))
                        }
                        WhenAction::Reinit { state, value } => {
                            format!("reinit({}, {})", dae.name(*state), show(*value))
                        }
                        WhenAction::Terminate { message } => format!("terminate({message:?})"),
                        WhenAction::Assert { condition, message } => {
                            format!("assert({}, {message:?})", show(*condition))
                        }
                    };
                    let _ = writeln!(o, "      {text}");
                }
            }
        }
    }
}
