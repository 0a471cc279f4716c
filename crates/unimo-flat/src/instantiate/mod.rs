//! Instantiation: walks a class with its modifications and produces the flat model —
//! variables with full names and merged attributes, equations with full references,
//! `for` equations unrolled, structural `if`s decided, connections recorded.

use crate::error::FlatError;
use crate::eval::{self, EvalError, Value};
use crate::flat::{FlatModel, FlatType, VarId};
use crate::lookup::Found;
use crate::modif::{Mod, Scope};
use crate::tree::{ClassId, ClassTree};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use smol_str::SmolStr;
use unimo_source::{Diagnostic, Span};
use unimo_syntax::ast::*;

mod class_body;
mod component;
mod constants;
mod elements;
mod equations;
mod exprs;
mod function_calls;
mod inner_outer;

/// Attributes a variable of a predefined type may be modified with.
const ATTRIBUTES: &[&str] = &[
    "start",
    "fixed",
    "nominal",
    "min",
    "max",
    "unit",
    "quantity",
    "displayUnit",
    "stateSelect",
    "unbounded",
];

/// Deepest component nesting followed (recursive models are errors).
const MAX_DEPTH: usize = 100;

/// How often one class may appear among an instance's enclosing instances.
const MAX_SELF_NESTING: usize = 8;

/// Most scalar variables and component instances one model may have: beyond it the
/// model is refused (`E2014`) rather than exhausting memory.
pub const MAX_SCALARS: usize = 4_000_000;

/// One `connect` as written, with full paths and faces.
#[derive(Clone, Debug)]
pub struct Connect {
    pub a: ComponentRef,
    pub b: ComponentRef,
    /// Whether each side is an outside connector (declared in the class that connects).
    pub a_outside: bool,
    pub b_outside: bool,
    pub span: Span,
}

pub(crate) struct Instantiator<'t, 'p> {
    pub tree: &'t mut ClassTree<'p>,
    pub model: FlatModel,
    /// Variables by name, built on demand (only parameter evaluation asks): the first
    /// `indexed` variables are in it.
    var_index: HashMap<String, VarId>,
    indexed: usize,
    pub connects: Vec<Connect>,
    pub diags: Vec<Diagnostic>,
    values: HashMap<String, Value>,
    /// The element being instantiated is declared `final` (read by `builtin_var`).
    element_final: bool,
    /// Modifiers applied to the top-level class (parameter overrides).
    pub(crate) top_modifiers: Mod,
    pub(crate) evaluating: HashSet<String>,
    /// Instances whose bases are being instantiated: (instance key, class, modifier,
    /// scope). A base's modifier or condition may read the instance's own parameters,
    /// which are declared after its bases (`extends Port(use = useHeat)`).
    pub(crate) pending_own: Vec<(String, ClassId, Mod, Scope)>,
    /// The classes of the instances enclosing the current one (components only).
    ancestors: Vec<ClassId>,
    /// Paths of conditional components that are absent.
    pub absent: Vec<String>,
    /// Instance keys of the expandable connectors (their declared members are only
    /// potentially present, see `expandable.rs`).
    pub expandable: Vec<String>,
    /// Instance keys of the components whose class is a connector: `c.p` in a
    /// `connect` is an outside connector when `c` is one (spec 9.1.2).
    connector_keys: HashSet<String>,
    /// Element names declared so far in the instances being instantiated (one level
    /// per [`Self::class_body`], shared with its bases), with where; innermost last.
    /// `None`: the class is known to declare no name twice (checked at its first
    /// instance: which elements a class has, inherited ones included, does not depend
    /// on the instance), so the level checks nothing.
    declared: Vec<Option<HashMap<SmolStr, Span>>>,
    /// Whether the innermost level found a duplicate.
    duplicate_found: Vec<bool>,
    /// Classes whose elements were checked and have no duplicate names.
    duplicate_free: HashSet<ClassId>,
    /// Emptied levels of `declared`, kept for reuse (no map allocated per instance).
    declared_pool: Vec<HashMap<SmolStr, Span>>,
    /// `inner` components visible from the current instance, innermost last:
    /// (name, instance path of the inner component).
    inners: Vec<(SmolStr, Vec<RefPart>)>,
    /// Nesting of compile-time function calls.
    pub(crate) call_depth: usize,
    /// `input`/`output` of the enclosing structured component, passed to its variables.
    inherited_causality: Option<Causality>,
    /// The `input`/`output` of the short class definitions the last
    /// [`Self::resolve_type_dims`] followed (`connector RealInput = input Real`), the
    /// outermost one's.
    type_causality: Option<Causality>,
    /// Scalars and instances created so far, against [`MAX_SCALARS`].
    budget_used: usize,
    /// Set when the budget ran out: instantiation stops.
    stopped: bool,
    /// Instance keys of `outer` components, with the path of the `inner` they stand for.
    outer_alias: HashMap<String, Vec<RefPart>>,
    /// The types of `inner` components by instance key (None: not known).
    inner_types: HashMap<String, Option<Found>>,
    /// Inner components added at the top for `outer` ones without inner: (name, type,
    /// path).
    default_inners: Vec<(SmolStr, Found, Vec<RefPart>)>,
    depth: usize,
    /// Record classes the model uses, in the order first seen.
    pub(crate) records_used: Vec<ClassId>,
    /// Redeclared classes by (instance key, class name): what the name means inside
    /// that instance (`redeclare model Sensor = OffsetSensor`).
    pub(crate) class_redeclares: HashMap<(String, SmolStr), ClassId>,
    /// The scope each class redeclared in a modifier was written in (its modifiers
    /// read names there: `redeclare function f = g(k = p)`).
    pub(crate) detached_scopes: HashMap<ClassId, Scope>,
    /// Class paths looked up from a class (without redeclarations), by (class, path).
    pub(crate) type_cache: HashMap<(ClassId, SmolStr), Option<Found>>,
    /// The type of a component clause by (class, address of the clause's type name in
    /// the class's syntax tree, which the tree keeps alive), and whether it has no
    /// constraining modifiers: only filled and used while there are no class
    /// redeclarations.
    clause_types: HashMap<(ClassId, usize), (Option<Found>, bool)>,
    /// Per class: declared `replaceable` in its parent, and its constraining clause.
    pub(crate) constraint_cache: HashMap<ClassId, Option<(bool, Option<ConstrainingClause>)>>,
}

/// The type a component turns out to have.
pub(crate) enum Kind {
    Builtin(FlatType),
    Class(ClassId),
}

fn part(name: &str, span: Span) -> RefPart {
    RefPart {
        name: Ident {
            text: SmolStr::new(name),
            span,
        },
        subscripts: Vec::new(),
    }
}

fn int_expr(i: i64, span: Span) -> Expr {
    Expr {
        kind: ExprKind::Integer(i),
        span,
    }
}

/// The instance key of a path (all subscripts included).
pub(crate) fn instance_key(path: &[RefPart]) -> String {
    let mut k = eval::var_key_parts(path);
    if let Some(last) = path.last() {
        k.push_str(&unimo_syntax::print::subscripts(&last.subscripts));
    }
    k
}

/// `getInstanceName()` in the instance at `prefix` of model `model` (spec 3.7.4.6): the
/// model's own name (without its package, as the specification's example
/// `Vehicle.engine.controller` of `MyLib.Vehicle` shows) and the instance's path.
fn instance_name(model: &str, prefix: &[RefPart], span: Span) -> Expr {
    let mut text = crate::flat::split_name(model)
        .last()
        .copied()
        .unwrap_or(model)
        .to_owned();
    if !prefix.is_empty() {
        text.push('.');
        text.push_str(&instance_key(prefix));
    }
    Expr {
        kind: ExprKind::String(text),
        span,
    }
}

/// Whether an annotation sets `flag = true` (`annotation(Evaluate = true)`).
fn annotation_is_true(annotation: Option<&ClassModification>, flag: &str) -> bool {
    annotation.is_some_and(|a| {
        a.args.iter().any(|arg| match arg {
            Argument::Modify {
                name,
                modification: Some(m),
                ..
            } => {
                name.to_dotted() == flag
                    && matches!(
                        m.binding.as_ref().map(|b| &b.kind),
                        Some(ExprKind::Bool(true))
                    )
            }
            _ => false,
        })
    })
}

/// The instance key of a path, without the last part's subscripts.
pub(super) fn instance_key_no_subs(path: &[RefPart]) -> String {
    eval::var_key_parts(path)
}

/// `E2005`: `name` declared twice in the instance `owner`.
fn duplicate(name: &str, owner: &str, second: Span, first: Span) -> Diagnostic {
    FlatError::DuplicateElement {
        name: name.to_owned(),
        owner: owner.to_owned(),
        second,
        first,
    }
    .into()
}

/// All index tuples of an array of the given dimensions, in row-major order.
fn index_tuples(dims: &[usize]) -> Vec<Vec<i64>> {
    let mut out = vec![Vec::new()];
    for &d in dims {
        out = out
            .into_iter()
            .flat_map(|t| {
                (1..=d as i64).map(move |i| {
                    let mut t = t.clone();
                    t.push(i);
                    t
                })
            })
            .collect();
    }
    out
}

impl<'t, 'p> Instantiator<'t, 'p> {
    pub fn new(tree: &'t mut ClassTree<'p>) -> Self {
        Instantiator {
            tree,
            model: FlatModel::default(),
            var_index: HashMap::default(),
            indexed: 0,
            connects: Vec::new(),
            diags: Vec::new(),
            values: HashMap::default(),
            element_final: false,
            top_modifiers: Mod::default(),
            evaluating: HashSet::default(),
            pending_own: Vec::new(),
            ancestors: Vec::new(),
            absent: Vec::new(),
            expandable: Vec::new(),
            connector_keys: HashSet::default(),
            declared: Vec::new(),
            declared_pool: Vec::new(),
            duplicate_found: Vec::new(),
            duplicate_free: HashSet::default(),
            inners: Vec::new(),
            call_depth: 0,
            inherited_causality: None,
            type_causality: None,
            budget_used: 0,
            stopped: false,
            outer_alias: HashMap::default(),
            inner_types: HashMap::default(),
            default_inners: Vec::new(),
            records_used: Vec::new(),
            class_redeclares: HashMap::default(),
            detached_scopes: HashMap::default(),
            type_cache: HashMap::default(),
            constraint_cache: HashMap::default(),
            clause_types: HashMap::default(),
            depth: 0,
        }
    }

    /// The variable named `key` (a later declaration of the same name wins). The index
    /// catches up with the variables created since the last question: each variable
    /// is indexed once, and not at all in a model that evaluates no parameters.
    pub(crate) fn var_id(&mut self, key: &str) -> Option<VarId> {
        let n = self.model.vars.len();
        if self.indexed < n {
            self.var_index.reserve(n - self.indexed);
            for (i, v) in self.model.vars[self.indexed..].iter().enumerate() {
                self.var_index
                    .insert(v.name.clone(), VarId((self.indexed + i) as u32));
            }
            self.indexed = n;
        }
        self.var_index.get(key).copied()
    }

    /// Spends `n` of the size budget; false (and `E2014` once) when it is exhausted.
    fn spend(&mut self, n: usize, span: Span) -> bool {
        if self.stopped {
            return false;
        }
        self.budget_used = self.budget_used.saturating_add(n);
        if self.budget_used > MAX_SCALARS {
            self.stopped = true;
            self.report(FlatError::TooLarge {
                limit: MAX_SCALARS,
                span,
            });
            return false;
        }
        true
    }

    fn report(&mut self, e: FlatError) {
        self.diags.push(e.into());
    }

    /// `E2003`/`E2008`: a value needed at compile time (`context`) that cannot be
    /// evaluated.
    fn eval_error(&mut self, e: EvalError, context: &str) {
        let context = context.to_owned();
        self.report(match e {
            EvalError::NotConstant { span, what } => FlatError::NotConstant {
                context,
                what: what.to_string(),
                span,
            },
            EvalError::Unsupported { span, what } => FlatError::CannotEvaluate {
                context,
                what: what.to_string(),
                span,
            },
            EvalError::Cycle { span, name } => FlatError::EvaluationCycle {
                context,
                name: name.to_string(),
                span,
            },
        });
    }

    /// Instantiates the class `class` as the top-level model.
    pub fn run(&mut self, class: ClassId) {
        self.model.name = self.tree.full_name(class);
        if let ClassBody::Long { composition, .. } = &self.tree.get(class).def.body {
            self.model.experiment = composition.annotation.as_ref().and_then(|a| {
                a.args.iter().find_map(|arg| match arg {
                    Argument::Modify {
                        name,
                        modification: Some(m),
                        ..
                    } if name.to_dotted() == "experiment" => m.class_mod.clone(),
                    _ => None,
                })
            });
        }
        if self.tree.get(class).def.partial {
            let span = self.tree.get(class).def.name.span;
            self.report(FlatError::PartialModel {
                name: self.model.name.clone(),
                span,
            });
        }
        let top = std::mem::take(&mut self.top_modifiers);
        self.class_body(class_body::Body::new(class, &[], &top, None, true));
        let mut evaluated: Vec<String> = self.values.keys().cloned().collect();
        evaluated.sort();
        self.model.evaluated = evaluated;
    }

    /// Follows short class definitions to a long class or a predefined type,
    /// accumulating their modifiers (innermost last).
    fn resolve_type(&mut self, found: Found, m: &Mod) -> Option<(Kind, Mod)> {
        self.resolve_type_dims(found, m.clone())
            .map(|(k, m, _)| (k, m))
    }

    /// Like [`resolve_type`], also returning the array dimensions the short class
    /// definitions add (`type Position3 = Real[3]`), outermost first, with their scope.
    #[allow(clippy::type_complexity)]
    pub(crate) fn resolve_type_dims(
        &mut self,
        mut found: Found,
        mut m: Mod,
    ) -> Option<(Kind, Mod, Vec<(Subscript, Scope)>)> {
        let mut type_dims: Vec<(Subscript, Scope)> = Vec::new();
        self.type_causality = None;
        for _ in 0..MAX_DEPTH {
            let c = match found {
                Found::Builtin(b) => {
                    let t = match b {
                        "Real" => FlatType::Real,
                        "Integer" => FlatType::Integer,
                        "Boolean" => FlatType::Boolean,
                        "String" => FlatType::String,
                        // StateSelect and AssertionLevel are enumerations.
                        other => FlatType::Enumeration {
                            name: other.to_owned(),
                            literals: Vec::new(),
                        },
                    };
                    return Some((Kind::Builtin(t), m, type_dims));
                }
                Found::Component(_) => return None,
                Found::Class(c) => c,
            };
            let def = self.tree.get(c).def.clone();
            if crate::external::is_external_object(&def) {
                let name = self.tree.full_name(c);
                return Some((
                    Kind::Builtin(FlatType::ExternalObject { name }),
                    m,
                    type_dims,
                ));
            }
            match &def.body {
                ClassBody::Short {
                    causality,
                    base,
                    modification,
                    dims,
                    ..
                } => {
                    self.type_causality = self.type_causality.or(*causality);
                    let parent = self.tree.get(c).parent;
                    let dim_scope = Scope {
                        class: parent.unwrap_or(c),
                        prefix: std::sync::Arc::from([]),
                    };
                    type_dims.extend(dims.iter().map(|d| (d.clone(), dim_scope.clone())));
                    if let Some(cm) = modification {
                        let scope = Scope {
                            class: parent.unwrap_or(c),
                            prefix: std::sync::Arc::from([]),
                        };
                        m = m.over(&Mod::from_class_mod(cm, &scope));
                    }
                    let parts: Vec<&str> = base.parts.iter().map(|p| p.text.as_str()).collect();
                    found = self.tree.lookup_dotted(parent, &parts, false)?;
                }
                ClassBody::Enumeration { literals, .. } => {
                    let name = self.tree.full_name(c);
                    let lits: Vec<String> =
                        literals.iter().map(|l| l.name.text.to_string()).collect();
                    if !self.model.enumerations.iter().any(|(n, _)| *n == name) {
                        self.model.enumerations.push((name.clone(), lits.clone()));
                    }
                    return Some((
                        Kind::Builtin(FlatType::Enumeration {
                            name,
                            literals: lits,
                        }),
                        m,
                        type_dims,
                    ));
                }
                ClassBody::Long { composition, .. } if self.is_type_like(c) => {
                    // `type TypeReal extends Real; end TypeReal;` (the MSL's icons of
                    // types): a class that only extends a type is that type with the
                    // extends' modifier, as the short form would be.
                    let x = sole_extends(composition).expect("type-like");
                    let parts: Vec<&str> = x.base.parts.iter().map(|p| p.text.as_str()).collect();
                    let base = self.tree.lookup_dotted(Some(c), &parts, true)?;
                    if let Some(cm) = &x.modification {
                        let scope = Scope {
                            class: c,
                            prefix: std::sync::Arc::from([]),
                        };
                        m = m.over(&Mod::from_class_mod(cm, &scope));
                    }
                    found = base;
                }
                ClassBody::Long { .. } | ClassBody::Der { .. } => {
                    return Some((Kind::Class(c), m, type_dims))
                }
            }
        }
        None
    }
}

/// The one `extends` of a composition without components or sections (nested classes
/// and imports allowed: `type Orientation extends Real[4]; function
/// equalityConstraint ... end Orientation;`), or `None`.
fn sole_extends(c: &unimo_syntax::ast::Composition) -> Option<&unimo_syntax::ast::Extends> {
    if !c.sections.is_empty() || c.external.is_some() {
        return None;
    }
    let mut found = None;
    for e in &c.elements {
        match &e.kind {
            ElementKind::Extends(x) if found.is_none() => found = Some(x),
            ElementKind::Extends(_) | ElementKind::Component(_) => return None,
            ElementKind::Class(_) | ElementKind::Import(_) => {}
        }
    }
    found
}

impl Instantiator<'_, '_> {
    /// A long class that only extends a predefined type, a short type, or another such
    /// class (so a component of it is a scalar or an array of scalars).
    fn is_type_like(&mut self, class: ClassId) -> bool {
        let mut c = class;
        for _ in 0..MAX_DEPTH {
            let parts: Vec<SmolStr> = match &self.tree.get(c).def.body {
                ClassBody::Short { .. } => return true,
                ClassBody::Long {
                    composition,
                    extends: None,
                    ..
                } => match sole_extends(composition) {
                    Some(x) => x.base.parts.iter().map(|p| p.text.clone()).collect(),
                    None => return false,
                },
                _ => return false,
            };
            let parts: Vec<&str> = parts.iter().map(|p| p.as_str()).collect();
            match self.tree.lookup_dotted(Some(c), &parts, true) {
                Some(Found::Builtin(b)) => return b != "ExternalObject",
                Some(Found::Class(b)) => c = b,
                _ => return false,
            }
        }
        false
    }
}
