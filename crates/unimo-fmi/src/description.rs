//! `modelDescription.xml` for FMI 2.0 and 3.0, Model Exchange or Co-Simulation: every
//! variable with causality, variability, initial, start, unit and description, the
//! derivative links, the event indicators and the model structure.

use crate::model::{Causality, Compiled, Variable};
use std::fmt::Write;
use unimo_dae::dae::{ScalarKind, ScalarType};

/// FMI 2.0 or 3.0.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Version {
    Fmi2,
    Fmi3,
}

/// Model Exchange or Co-Simulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    ModelExchange,
    CoSimulation,
}

/// What the description says besides the variables.
pub struct Header<'a> {
    pub model_name: &'a str,
    pub description: &'a str,
    pub identifier: &'a str,
    pub token: &'a str,
    pub version: Version,
    pub kind: Kind,
    /// start, stop, tolerance, output interval.
    pub experiment: (f64, f64, f64, f64),
}

/// A C identifier made of the model's name (`Modelica.X.First` -> `Modelica_X_First`).
pub fn identifier(model_name: &str) -> String {
    let mut id: String = model_name
        .trim_matches('\'')
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if !id.starts_with(|c: char| c.is_ascii_alphabetic()) {
        id.insert(0, 'm');
    }
    id
}

/// The instantiation token (FMI 2: guid): a hash of the model text and the variable
/// table, so a library never runs resources that do not match its description.
pub fn token(text: &str, variables: &[Variable]) -> String {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut feed = |bytes: &[u8]| {
        for &b in bytes {
            hash ^= u64::from(b);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    feed(text.as_bytes());
    for v in variables {
        feed(v.name.as_bytes());
        feed(&[0]);
    }
    let hi = hash;
    let lo = hash.rotate_left(29) ^ 0x9e37_79b9_7f4a_7c15;
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        hi >> 32,
        (hi >> 16) & 0xffff,
        hi & 0xffff,
        lo >> 48,
        lo & 0xffff_ffff_ffff
    )
}

fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 && c != '\t' => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

fn number(v: f64) -> String {
    if v.is_finite() {
        format!("{v:?}")
    } else if v.is_nan() {
        "NaN".into()
    } else if v > 0.0 {
        "INF".into()
    } else {
        "-INF".into()
    }
}

/// (causality, variability, initial) as FMI writes them.
fn attributes(v: &Variable) -> (&'static str, &'static str, Option<&'static str>) {
    let variability = match (v.kind, v.ty) {
        (ScalarKind::Constant, _) => "constant",
        (ScalarKind::Parameter, _) => "fixed",
        (ScalarKind::Continuous | ScalarKind::Derivative, ScalarType::Real) => "continuous",
        _ => "discrete",
    };
    match v.causality {
        Causality::Parameter => ("parameter", variability, Some("exact")),
        Causality::CalculatedParameter => ("calculatedParameter", variability, Some("calculated")),
        Causality::Input => ("input", variability, None),
        Causality::Output => ("output", variability, Some("calculated")),
        Causality::Local if variability == "constant" || v.start_exact => {
            ("local", variability, Some("exact"))
        }
        Causality::Local => ("local", variability, Some("calculated")),
    }
}

/// Whether the description gives the variable a start value.
fn has_start(v: &Variable) -> bool {
    let (_, _, initial) = attributes(v);
    initial == Some("exact") || v.causality == Causality::Input
}

/// The value references of the initial unknowns (FMI 2.0 3.2.3 / FMI 3.0 2.4.8):
/// outputs, calculated parameters, states (but those with `initial = "exact"`) and
/// derivatives, in order.
fn initial_unknowns(c: &Compiled) -> Vec<u32> {
    let mut out: Vec<u32> = c
        .variables
        .iter()
        .filter(|v| {
            matches!(
                v.causality,
                Causality::Output | Causality::CalculatedParameter
            )
        })
        .map(|v| v.scalar)
        .collect();
    for &(x, dx) in &c.states {
        if !c.variables[x as usize].start_exact {
            out.push(x);
        }
        out.push(dx);
    }
    out.sort_unstable();
    out.dedup();
    out
}

fn units(c: &Compiled) -> Vec<&str> {
    let mut units: Vec<&str> = c
        .variables
        .iter()
        .filter_map(|v| v.unit.as_deref())
        .collect();
    units.sort_unstable();
    units.dedup();
    units
}

/// The whole `modelDescription.xml`.
pub fn write(h: &Header<'_>, c: &Compiled) -> String {
    let mut x = String::new();
    let n_roots = c.model.roots.len();
    let version = match h.version {
        Version::Fmi2 => "2.0",
        Version::Fmi3 => "3.0",
    };
    let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = write!(
        x,
        r#"<fmiModelDescription fmiVersion="{version}" modelName="{}" description="{}" generationTool="unimo {}" variableNamingConvention="flat""#,
        escape(h.model_name),
        escape(h.description),
        env!("CARGO_PKG_VERSION"),
    );
    match h.version {
        Version::Fmi2 => {
            let _ = writeln!(
                x,
                r#" guid="{}" numberOfEventIndicators="{n_roots}">"#,
                h.token
            );
        }
        Version::Fmi3 => {
            let _ = writeln!(x, r#" instantiationToken="{}">"#, h.token);
        }
    }
    let kind = match h.kind {
        Kind::ModelExchange => "ModelExchange",
        Kind::CoSimulation => "CoSimulation",
    };
    // A collision world starts its sweep (`gaps[1]`'s pass-through check) at each
    // accepted step: Model Exchange needs `CompletedIntegratorStep` then.
    let world = c.model.collision.is_some();
    let extra = match (h.version, h.kind) {
        (Version::Fmi2, Kind::ModelExchange) if world => "",
        (Version::Fmi2, Kind::ModelExchange) => r#" completedIntegratorStepNotNeeded="true""#,
        (Version::Fmi3, Kind::ModelExchange) if world => r#" needsCompletedIntegratorStep="true""#,
        (Version::Fmi3, Kind::ModelExchange) => r#" needsCompletedIntegratorStep="false""#,
        (_, Kind::CoSimulation) => r#" canHandleVariableCommunicationStepSize="true""#,
    };
    let memory = match h.version {
        Version::Fmi2 => r#" canNotUseMemoryManagementFunctions="true""#,
        Version::Fmi3 => "",
    };
    let _ = writeln!(
        x,
        r#"  <{kind} modelIdentifier="{}"{extra}{memory}/>"#,
        h.identifier
    );
    let units = units(c);
    if !units.is_empty() {
        let _ = writeln!(x, "  <UnitDefinitions>");
        for u in units {
            let _ = writeln!(x, r#"    <Unit name="{}"/>"#, escape(u));
        }
        let _ = writeln!(x, "  </UnitDefinitions>");
    }
    let (start, stop, tolerance, step) = h.experiment;
    let _ = writeln!(
        x,
        r#"  <DefaultExperiment startTime="{}" stopTime="{}" tolerance="{}" stepSize="{}"/>"#,
        number(start),
        number(stop),
        number(tolerance),
        number(step)
    );
    match h.version {
        Version::Fmi2 => write_fmi2_variables(&mut x, c),
        Version::Fmi3 => write_fmi3_variables(&mut x, c),
    }
    x.push_str("</fmiModelDescription>\n");
    x
}

/// A variable's opening tag `<element` with its name, value reference, causality,
/// variability and, where it has them, `initial` and description (FMI 2.0 and 3.0 alike).
fn write_variable_attributes(x: &mut String, element: &str, v: &Variable) {
    let (causality, variability, initial) = attributes(v);
    let _ = write!(
        x,
        r#"    <{element} name="{}" valueReference="{}" causality="{causality}" variability="{variability}""#,
        escape(&v.name),
        v.scalar
    );
    if let Some(i) = initial {
        let _ = write!(x, r#" initial="{i}""#);
    }
    if !v.description.is_empty() {
        let _ = write!(x, r#" description="{}""#, escape(&v.description));
    }
}

fn write_fmi2_variables(x: &mut String, c: &Compiled) {
    let _ = writeln!(x, "  <ModelVariables>");
    for v in &c.variables {
        write_variable_attributes(x, "ScalarVariable", v);
        let element = match v.ty {
            ScalarType::Real => "Real",
            ScalarType::Boolean => "Boolean",
            ScalarType::Integer | ScalarType::Enumeration(_) => "Integer",
        };
        let _ = write!(x, "><{element}");
        start_unit_derivative(x, v, 1);
        let _ = writeln!(x, "/></ScalarVariable>");
    }
    let _ = writeln!(x, "  </ModelVariables>");
    let _ = writeln!(x, "  <ModelStructure>");
    let unknowns = |x: &mut String, tag: &str, refs: &[u32]| {
        if refs.is_empty() {
            return;
        }
        let _ = writeln!(x, "    <{tag}>");
        for r in refs {
            let _ = writeln!(x, r#"      <Unknown index="{}"/>"#, r + 1);
        }
        let _ = writeln!(x, "    </{tag}>");
    };
    unknowns(x, "Outputs", &outputs(c));
    let derivatives: Vec<u32> = c.states.iter().map(|s| s.1).collect();
    unknowns(x, "Derivatives", &derivatives);
    unknowns(x, "InitialUnknowns", &initial_unknowns(c));
    let _ = writeln!(x, "  </ModelStructure>");
}

/// The `start`, `unit` and `derivative` attributes of a variable's element, both
/// versions: the derivative names its state's value reference plus `offset` (FMI 2.0
/// counts variables from 1, FMI 3.0 names the value reference).
fn start_unit_derivative(x: &mut String, v: &Variable, offset: u32) {
    if let (Some(s), true) = (v.start, has_start(v)) {
        let start = match v.ty {
            ScalarType::Boolean => (s != 0.0).to_string(),
            ScalarType::Integer | ScalarType::Enumeration(_) => (s as i64).to_string(),
            ScalarType::Real => number(s),
        };
        let _ = write!(x, r#" start="{start}""#);
    }
    if let Some(u) = &v.unit {
        let _ = write!(x, r#" unit="{}""#, escape(u));
    }
    if let Some(state) = v.derivative_of {
        let _ = write!(x, r#" derivative="{}""#, state + offset);
    }
}

fn outputs(c: &Compiled) -> Vec<u32> {
    c.variables
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .map(|v| v.scalar)
        .collect()
}

/// FMI 3.0: the variables, then `time` (the independent variable) and the event
/// indicators as variables after them ([`fmi3_extra_references`]).
fn write_fmi3_variables(x: &mut String, c: &Compiled) {
    let _ = writeln!(x, "  <ModelVariables>");
    let (time, first_indicator) = fmi3_extra_references(c);
    let _ = writeln!(
        x,
        r#"    <Float64 name="time" valueReference="{time}" causality="independent" variability="continuous" description="Simulation time"/>"#
    );
    for v in &c.variables {
        let element = match v.ty {
            ScalarType::Real => "Float64",
            ScalarType::Boolean => "Boolean",
            ScalarType::Integer | ScalarType::Enumeration(_) => "Int32",
        };
        write_variable_attributes(x, element, v);
        start_unit_derivative(x, v, 0);
        let _ = writeln!(x, "/>");
    }
    for k in 0..c.model.roots.len() {
        let _ = writeln!(
            x,
            r#"    <Float64 name="_eventIndicator{k}" valueReference="{}" causality="local" variability="continuous" initial="calculated" description="zero crossing {}"/>"#,
            first_indicator + k as u32,
            escape(&c.model.root_names[k])
        );
    }
    let _ = writeln!(x, "  </ModelVariables>");
    let _ = writeln!(x, "  <ModelStructure>");
    for r in outputs(c) {
        let _ = writeln!(x, r#"    <Output valueReference="{r}"/>"#);
    }
    for &(_, dx) in &c.states {
        let _ = writeln!(
            x,
            r#"    <ContinuousStateDerivative valueReference="{dx}"/>"#
        );
    }
    for r in initial_unknowns(c) {
        let _ = writeln!(x, r#"    <InitialUnknown valueReference="{r}"/>"#);
    }
    for k in 0..c.model.roots.len() {
        let _ = writeln!(
            x,
            r#"    <EventIndicator valueReference="{}"/>"#,
            first_indicator + k as u32
        );
    }
    let _ = writeln!(x, "  </ModelStructure>");
}

/// FMI 3.0's value references after the scalars: `time`, then the first event
/// indicator.
pub fn fmi3_extra_references(c: &Compiled) -> (u32, u32) {
    let n = c.variables.len() as u32;
    (n, n + 1)
}
