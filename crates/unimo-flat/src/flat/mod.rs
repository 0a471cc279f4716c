//! The flat model: variables with full names, equations and algorithms with full
//! references, and its printer (flat Modelica that unimo parses back).
//!
//! Naming: a variable's name is its instance path (`body.r`, `pins[2].v`); array
//! variables keep their dimensions (`Real 'body.r'[3]`) and array equations stay array
//! equations — scalarization is the lowering stage's job. When printed, a dotted or
//! subscripted path becomes one quoted identifier (`'body.r'`), which is standard
//! Modelica and reads back as the same name.

use smol_str::SmolStr;
use unimo_source::Span;
use unimo_syntax::ast::{
    Causality, ClassModification, ComponentRef, Equation, Expr, RefPart, Statement,
};

mod printer;
mod walk;

pub use printer::printable;
pub(crate) use printer::type_name;
pub use walk::{
    for_each_call, for_each_equation_expr, for_each_ref, for_each_value_ref, rewrite_refs,
};

/// Index of a variable in [`FlatModel::vars`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct VarId(pub u32);

#[derive(Clone, Debug, PartialEq)]
pub enum FlatType {
    Real,
    Integer,
    Boolean,
    String,
    /// An enumeration type: its full class name and literals.
    Enumeration {
        name: String,
        literals: Vec<String>,
    },
    /// An external object class (`extends ExternalObject`): its full name. Values are
    /// handles its `constructor` function makes.
    ExternalObject {
        name: String,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Variability {
    Constant,
    Parameter,
    Discrete,
    Continuous,
}

#[derive(Clone, Debug)]
pub struct FlatVar {
    /// The instance path (`body.r`, `pins[2].v`).
    pub name: String,
    pub ty: FlatType,
    pub variability: Variability,
    pub causality: Option<Causality>,
    pub flow: bool,
    /// Evaluated array dimensions (empty: scalar).
    pub dims: Vec<usize>,
    pub binding: Option<Box<Expr>>,
    /// `start`, `fixed`, `nominal`, `min`, `max`, `unit`, `stateSelect`, ... in order
    /// of first appearance.
    pub attributes: Vec<(SmolStr, Expr)>,
    /// `each` applied to an attribute of an array variable.
    pub each_attributes: Vec<SmolStr>,
    pub description: Option<String>,
    /// Declared in the top-level class (its inputs are known from outside).
    pub top_level: bool,
    /// A parameter declared with `annotation(Evaluate = true)`: its value is fixed at
    /// translation (a capacitance of 0 removes the capacitor's derivative).
    pub evaluate: bool,
    /// Declared `final`, or given a value by a `final` modifier: no modifier may
    /// change it (spec 7.2.6).
    pub is_final: bool,
    pub origin: Span,
}

impl FlatVar {
    /// Number of scalars.
    pub fn size(&self) -> usize {
        self.dims
            .iter()
            .fold(1usize, |acc, &n| acc.saturating_mul(n))
    }
}

/// The whole model after instantiation.
#[derive(Clone, Debug, Default)]
pub struct FlatModel {
    /// Full name of the instantiated class.
    pub name: String,
    pub vars: Vec<FlatVar>,
    pub equations: Vec<Equation>,
    pub initial_equations: Vec<Equation>,
    pub algorithms: Vec<Vec<Statement>>,
    pub initial_algorithms: Vec<Vec<Statement>>,
    /// `annotation(experiment(...))` of the class, as written.
    pub experiment: Option<ClassModification>,
    /// Enumeration types used by variables, by full name.
    pub enumerations: Vec<(String, Vec<String>)>,
    /// The user functions called (transitively), sorted by name.
    pub functions: Vec<crate::functions::FlatFunction>,
    /// The record types the model uses (components, constructors, function
    /// arguments), sorted by name.
    pub records: Vec<crate::functions::FlatRecord>,
    /// Every record instance by path (`z`, `body.frame`, `c[2]`) with its record type's
    /// full name; its fields are variables named `path.field`.
    pub record_instances: Vec<(String, String)>,
    /// Parameters and constants whose values instantiation evaluated (array sizes,
    /// `for` ranges, conditions of conditional components and structural `if`s, folded
    /// subscripts, and what those depend on), sorted: changing one changes the
    /// model's structure, so it needs flattening again.
    pub evaluated: Vec<String>,
    /// The components the animation draws, in instantiation order (see
    /// [`crate::visual`]).
    pub visuals: Vec<FlatVisual>,
}

/// A component whose class (or a base of it) declares `annotation(__unimo_visual(...))`.
#[derive(Clone, Debug)]
pub struct FlatVisual {
    /// The instance path (`ball`, `balls[2]`, `a.b`).
    pub path: String,
    /// The component's class, full name.
    pub class: String,
    /// The annotation's arguments as written: names in them are relative to the instance.
    pub spec: ClassModification,
}

/// Array dimensions as text: `scalar` or `[3, 2]`.
pub fn fmt_dims(d: &[usize]) -> String {
    if d.is_empty() {
        "scalar".into()
    } else {
        let parts: Vec<String> = d.iter().map(|x| x.to_string()).collect();
        format!("[{}]", parts.join(", "))
    }
}

/// Splits a dotted name at the dots outside quoted identifiers
/// (`'Pkg.f'.x` is `'Pkg.f'` and `x`).
pub fn split_name(name: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut quoted = false;
    let bytes = name.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'\\' if quoted => i += 1,
            b'\'' => quoted = !quoted,
            b'.' if !quoted => {
                out.push(&name[start..i]);
                start = i + 1;
            }
            _ => {}
        }
        i += 1;
    }
    out.push(&name[start..]);
    out
}

/// A flat reference: the instance path as reference parts.
pub fn path_ref(parts: Vec<RefPart>, span: Span) -> ComponentRef {
    ComponentRef {
        global: false,
        parts,
        span,
    }
}

/// `name` quoted when it is not a plain identifier.
pub fn quote(name: &str) -> String {
    let plain = name
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !unimo_syntax::lexer::is_keyword(name);
    if plain || (name.starts_with('\'') && name.ends_with('\'') && name.len() > 1) {
        name.to_owned()
    } else {
        format!("'{}'", name.replace('\\', "\\\\").replace('\'', "\\'"))
    }
}

impl FlatModel {
    /// Each variable's position in `vars`, by name.
    pub(crate) fn var_positions(&self) -> rustc_hash::FxHashMap<&str, usize> {
        (self.vars.iter().enumerate())
            .map(|(k, v)| (v.name.as_str(), k))
            .collect()
    }

    /// Number of scalar variables by variability.
    pub fn count(&self, var: Variability) -> usize {
        self.vars
            .iter()
            .filter(|v| v.variability == var)
            .map(FlatVar::size)
            .sum()
    }
}
