//! Instantiation: walks a class with its modifications and produces the flat model —
//! variables with full names and merged attributes, equations with full references,
//! `for` equations unrolled, structural `if`s decided, connections recorded.

use crate::eval::{self, Env, EvalError, Value};
use crate::flat::{FlatModel, FlatType, FlatVar, VarId, Variability};
use crate::lookup::{is_builtin_function, Found};
use crate::modif::{Bound, Mod, Scope};
use crate::tree::{ClassId, ClassTree};
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use smol_str::SmolStr;
use unimo_source::{Diagnostic, Span};
use unimo_syntax::ast::*;

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
    /// Scalars and instances created so far, against [`MAX_SCALARS`].
    budget_used: usize,
    /// Set when the budget ran out: instantiation stops.
    stopped: bool,
    /// Instance keys of `outer` components, with the path of the `inner` they stand for.
    outer_alias: HashMap<String, Vec<RefPart>>,
    depth: usize,
    /// Record classes the model uses, in the order first seen.
    pub(crate) records_used: Vec<ClassId>,
    /// Redeclared classes by (instance key, class name): what the name means inside
    /// that instance (`redeclare model Sensor = OffsetSensor`).
    pub(crate) class_redeclares: HashMap<(String, SmolStr), ClassId>,
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
fn instance_key_no_subs(path: &[RefPart]) -> String {
    eval::var_key_parts(path)
}

/// `E2005`: `name` declared twice in the instance `owner`.
fn duplicate(name: &str, owner: &str, second: Span, first: Span) -> Diagnostic {
    Diagnostic::error("E2005", format!("`{name}` is declared twice in `{owner}`"))
        .at(second, "second declaration")
        .with_label(first, "first declared here (possibly in a base class)")
        .with_help("rename one of them; an inherited element and a local one share one name space")
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
            declared: Vec::new(),
            declared_pool: Vec::new(),
            duplicate_found: Vec::new(),
            duplicate_free: HashSet::default(),
            inners: Vec::new(),
            call_depth: 0,
            inherited_causality: None,
            budget_used: 0,
            stopped: false,
            outer_alias: HashMap::default(),
            records_used: Vec::new(),
            class_redeclares: HashMap::default(),
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
            self.diags.push(
                Diagnostic::error(
                    "E2014",
                    format!(
                        "the model is too large (more than {MAX_SCALARS} scalars and instances)"
                    ),
                )
                .at(span, "the limit was passed here")
                .with_help("check the array sizes and `for` ranges"),
            );
            return false;
        }
        true
    }

    fn error(&mut self, code: &'static str, message: String, span: Span, label: &str) {
        self.diags
            .push(Diagnostic::error(code, message).at(span, label));
    }

    fn eval_error(&mut self, e: EvalError, context: &str) {
        let (span, what, code) = match e {
            EvalError::NotConstant { span, what } => (
                span,
                format!("depends on {what}, which is not a known parameter or constant"),
                "E2003",
            ),
            EvalError::Unsupported { span, what } => {
                (span, format!("cannot evaluate {what}"), "E2003")
            }
            EvalError::Cycle { span, name } => (
                span,
                format!("parameter `{name}` depends on itself"),
                "E2008",
            ),
        };
        self.diags.push(
            Diagnostic::error(code, format!("{context}: {what}"))
                .at(span, "needed at compile time")
                .with_help("sizes, `for` ranges and conditions of conditional components and structural `if`s must be parameters or constants"),
        );
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
            self.error(
                "E2009",
                format!(
                    "class `{}` is partial and cannot be simulated",
                    self.model.name
                ),
                span,
                "declared `partial`",
            );
        }
        let top = std::mem::take(&mut self.top_modifiers);
        self.class_body(class, &[], &top, None, true);
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
                    base,
                    modification,
                    dims,
                    ..
                } => {
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
                ClassBody::Long { .. } | ClassBody::Der { .. } => {
                    return Some((Kind::Class(c), m, type_dims))
                }
            }
        }
        None
    }

    /// Instantiates the elements and equations of `class` at `prefix`.
    fn class_body(
        &mut self,
        class: ClassId,
        prefix: &[RefPart],
        m: &Mod,
        variability: Option<Variability>,
        top: bool,
    ) {
        // A class inside itself (a record with a component of its own type): legal
        // only while conditions stop the recursion, which they do within a few levels;
        // past MAX_SELF_NESTING it would grow exponentially until memory runs out.
        let nesting = self.ancestors.iter().filter(|&&c| c == class).count();
        if nesting >= MAX_SELF_NESTING {
            if !self.stopped {
                self.stopped = true;
                let def = &self.tree.get(class).def;
                let (name, span) = (def.name.text.clone(), def.name.span);
                self.error(
                    "E2011",
                    format!("instances of `{name}` nested {MAX_SELF_NESTING} deep in each other (a recursive model?)"),
                    span,
                    "this class contains itself",
                );
            }
            return;
        }
        self.ancestors.push(class);
        let check = !self.duplicate_free.contains(&class);
        let level = check.then(|| self.declared_pool.pop().unwrap_or_default());
        self.declared.push(level);
        self.duplicate_found.push(false);
        self.class_body_inner(class, prefix, m, variability, top, true);
        self.ancestors.pop();
        let found = self.duplicate_found.pop().unwrap_or(true);
        if let Some(Some(mut level)) = self.declared.pop() {
            level.clear();
            self.declared_pool.push(level);
            if !found {
                self.duplicate_free.insert(class);
            }
        }
    }

    /// `check_mods`: whether modified names are checked here (not again in bases).
    fn class_body_inner(
        &mut self,
        class: ClassId,
        prefix: &[RefPart],
        m: &Mod,
        variability: Option<Variability>,
        top: bool,
        check_mods: bool,
    ) {
        if self.stopped {
            return;
        }
        if self.depth >= MAX_DEPTH {
            let span = self.tree.get(class).def.name.span;
            self.error(
                "E2011",
                format!("instances nested more than {MAX_DEPTH} deep (a recursive model?)"),
                span,
                "in this class",
            );
            return;
        }
        self.depth += 1;
        let def = self.tree.get(class).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            // A short class used as a model: instantiate its base with its modifiers.
            if let Some((Kind::Class(c), m2)) = self.resolve_type(Found::Class(class), m) {
                if c != class {
                    self.class_body(c, prefix, &m2, variability, top);
                }
            }
            self.depth -= 1;
            return;
        };
        let scope = Scope {
            class,
            prefix: std::sync::Arc::from(prefix),
        };
        let prefix_key = if prefix.is_empty() {
            String::new()
        } else {
            instance_key(prefix)
        };
        self.register_class_redeclares(class, composition, prefix, m);
        // `redeclare T x(...)` as an element of this class replaces the inherited `x`:
        // it travels into the bases like an extends modifier (under the instance's).
        let mut own_redeclares = Mod::default();
        for e in &composition.elements {
            if let (true, ElementKind::Component(cc)) = (e.redeclare, &e.kind) {
                for d in &cc.components {
                    let mut dm = d
                        .modification
                        .as_ref()
                        .map(|dm| Mod::from_modification(dm, &scope))
                        .unwrap_or_default();
                    dm.redeclare = Some((cc.type_name.clone(), scope.clone()));
                    own_redeclares.children.push((d.name.text.clone(), dm));
                }
            }
        }
        let has_bases = crate::values::def_has_bases(&def);
        if has_bases {
            self.pending_own
                .push((prefix_key.clone(), class, m.clone(), scope.clone()));
        }
        // A class extension `model extends A(m)` first inherits the original `A`.
        if let ClassBody::Long {
            extends: Some(ext), ..
        } = &def.body
        {
            if let Some(original) = self.tree.extended_original(class) {
                let ext = ext
                    .modification
                    .as_ref()
                    .map(|cm| Mod::from_class_mod(cm, &scope))
                    .unwrap_or_default();
                let base_mod = m.over(&own_redeclares.over(&ext));
                self.class_body_inner(original, prefix, &base_mod, variability, top, false);
            }
        }
        // Inherited elements first, each base with the extends modifier under ours.
        for e in &composition.elements {
            if let ElementKind::Extends(x) = &e.kind {
                let parts: Vec<&str> = x.base.parts.iter().map(|p| p.text.as_str()).collect();
                match self.tree.lookup_dotted(Some(class), &parts, true) {
                    Some(Found::Class(b)) => {
                        let ext = x
                            .modification
                            .as_ref()
                            .map(|cm| Mod::from_class_mod(cm, &scope))
                            .unwrap_or_default();
                        let base_mod = m.over(&own_redeclares.over(&ext));
                        self.class_body_inner(b, prefix, &base_mod, variability, top, false);
                    }
                    Some(Found::Builtin("ExternalObject")) => {} // an external object class
                    Some(Found::Builtin(_)) => {
                        self.error("E2012", "extending a predefined type is only allowed in a short class definition".into(), x.base.span, "here");
                    }
                    _ => {} // reported by the name check
                }
            }
        }
        if has_bases {
            self.pending_own.pop();
        }
        if check_mods {
            self.check_modified_names(class, composition, m);
        }
        // `inner` components of this instance are visible to `outer` ones below it.
        let inners_before = self.inners.len();
        for e in &composition.elements {
            if let (true, ElementKind::Component(cc)) = (e.inner, &e.kind) {
                for d in &cc.components {
                    let mut path = prefix.to_vec();
                    path.push(part(&d.name.text, d.name.span));
                    self.inners.push((d.name.text.clone(), path));
                }
            }
        }
        // `outer` components first: parameter bindings may refer through them.
        for e in &composition.elements {
            if let (true, false, false, ElementKind::Component(cc)) =
                (e.outer, e.inner, e.redeclare, &e.kind)
            {
                for d in &cc.components {
                    self.outer_component(&scope, d);
                }
            }
        }
        // Parameters and constants first: sizes and conditions of the others use them.
        for pass in 0..2 {
            for e in &composition.elements {
                let ElementKind::Component(cc) = &e.kind else {
                    continue;
                };
                let is_param = matches!(
                    cc.prefix.variability,
                    Some(
                        unimo_syntax::ast::Variability::Parameter
                            | unimo_syntax::ast::Variability::Constant
                    )
                );
                if (pass == 0) != is_param {
                    continue;
                }
                if e.redeclare {
                    continue; // instantiated in the base it replaces an element of
                }
                for d in &cc.components {
                    if e.outer && !e.inner {
                        continue; // aliased above
                    }
                    if let Some(child) = m.child(&d.name.text) {
                        self.check_element_modifier(e, d, child);
                    }
                    // `replaceable T x constrainedby C(mods)`: the constraining
                    // modifiers apply to `x`, whatever type it ends up with.
                    if let Some(cm) = e
                        .constrainedby
                        .as_ref()
                        .and_then(|c| c.modification.as_ref())
                    {
                        let cmod = Mod::from_class_mod(cm, &scope);
                        let mut m2 = m.clone();
                        let name = d.name.text.clone();
                        let child = m.child(&name).cloned().unwrap_or_default().over(&cmod);
                        m2.children.retain(|(n, _)| *n != name);
                        m2.children.push((name, child));
                        self.element_final = e.is_final;
                        self.component(&scope, &prefix_key, cc, d, &m2, variability, top);
                        continue;
                    }
                    self.element_final = e.is_final;
                    self.component(&scope, &prefix_key, cc, d, m, variability, top);
                }
            }
        }
        for s in &composition.sections {
            match s {
                Section::Equation(es) => {
                    let mut out = Vec::new();
                    for eq in &es.equations {
                        self.equation(eq, &scope, &mut Vec::new(), &mut out);
                    }
                    if es.initial {
                        self.model.initial_equations.extend(out);
                    } else {
                        self.model.equations.extend(out);
                    }
                }
                Section::Algorithm(al) => {
                    let mut stmts: Vec<Statement> = Vec::new();
                    self.model_statements(&al.statements, &scope, &mut Vec::new(), &mut stmts);
                    if al.initial {
                        self.model.initial_algorithms.push(stmts);
                    } else {
                        self.model.algorithms.push(stmts);
                    }
                }
            }
        }
        self.inners.truncate(inners_before);
        self.depth -= 1;
    }

    /// An `outer` component: no variables of its own; its references go to the nearest
    /// `inner` component of the same name in an enclosing instance (spec 5.4).
    fn outer_component(&mut self, scope: &Scope, d: &ComponentDecl) {
        let name = d.name.text.as_str();
        // Inners declared in this very instance do not count: they are siblings.
        let own = scope.prefix.len();
        let found = self
            .inners
            .iter()
            .rev()
            .find(|(n, path)| n == name && path.len() <= own)
            .map(|(_, p)| p.clone());
        let mut key_path = scope.prefix.to_vec();
        key_path.push(part(name, d.name.span));
        let key = instance_key(&key_path);
        match found {
            Some(inner) => {
                self.outer_alias.insert(key, inner);
            }
            None => self.diags.push(
                Diagnostic::error(
                    "E2013",
                    format!("`outer {name}` has no matching `inner` declaration"),
                )
                .at(d.name.span, "declared `outer` here")
                .with_help(format!("declare `inner ... {name}` in an enclosing model")),
            ),
        }
    }

    /// Every modified name must be an element of the class (or one of its bases).
    fn check_modified_names(&mut self, class: ClassId, _composition: &Composition, m: &Mod) {
        for (name, child) in &m.children {
            if !self.tree.has_component(class, name)
                && self.tree.member_class(class, name).is_none()
            {
                let span = child
                    .binding
                    .as_ref()
                    .map_or(Span::default(), |b| b.expr.span);
                let cname = self.tree.full_name(class);
                self.diags.push(
                    Diagnostic::error(
                        "E2004",
                        format!("modifier of `{name}`, which `{cname}` does not have"),
                    )
                    .at(span, "value given here")
                    .with_help(format!(
                        "the modified element must be declared in `{cname}` or a class it extends"
                    )),
                );
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn component(
        &mut self,
        scope: &Scope,
        prefix_key: &str,
        cc: &ComponentClause,
        d: &ComponentDecl,
        m: &Mod,
        inherited: Option<Variability>,
        top: bool,
    ) {
        let name = d.name.text.as_str();
        let Some(level) = self.declared.last_mut() else {
            return;
        };
        if let Some(seen) = level {
            if let Some(first) = seen.get(name).copied() {
                let owner = if scope.prefix.is_empty() {
                    self.model.name.clone()
                } else {
                    instance_key(&scope.prefix)
                };
                self.diags.push(duplicate(name, &owner, d.name.span, first));
                if let Some(f) = self.duplicate_found.last_mut() {
                    *f = true;
                }
                return;
            }
            seen.insert(d.name.text.clone(), d.name.span);
        }
        let decl_mod = d
            .modification
            .as_ref()
            .map(|dm| Mod::from_modification(dm, scope))
            .unwrap_or_default();
        let mut merged = match m.child(name) {
            Some(outer) => outer.clone().over_into(decl_mod),
            None => decl_mod,
        };
        // The full name (`s1.a.f`): the instance's key and the element's name.
        let key = if prefix_key.is_empty() {
            name.to_owned()
        } else {
            let mut k = String::with_capacity(prefix_key.len() + 1 + name.len());
            k.push_str(prefix_key);
            k.push('.');
            k.push_str(name);
            k
        };
        if let Some(cond) = &d.condition {
            let flat = self.expr(cond, scope, &mut Vec::new(), &mut Vec::new());
            match eval::eval(&flat, self, &mut Vec::new()) {
                Ok(Value::Bool(false)) => {
                    self.absent.push(key);
                    return;
                }
                Ok(Value::Bool(true)) => {}
                Ok(_) => self.error(
                    "E2003",
                    "the condition of a conditional component must be Boolean".into(),
                    cond.span,
                    "not Boolean",
                ),
                Err(e) => self.eval_error(e, "condition of a conditional component"),
            }
        }
        let found = match &merged.redeclare {
            Some((n, s)) => {
                let parts: Vec<&str> = n.parts.iter().map(|p| p.text.as_str()).collect();
                let found = self.tree.lookup_dotted(Some(s.class), &parts, false);
                if let Some(Found::Class(new)) = found {
                    self.check_plug_compatible(scope, cc, name, new, n.span);
                }
                found
            }
            None => {
                // Without class redeclarations a clause's type depends on its class
                // only: cached by (class, clause).
                let key = (scope.class, &cc.type_name as *const Name as usize);
                let cacheable = self.class_redeclares.is_empty();
                match self.clause_types.get(&key) {
                    Some(&(found, true)) if cacheable => found,
                    _ => {
                        let parts: Vec<&str> =
                            cc.type_name.parts.iter().map(|p| p.text.as_str()).collect();
                        let found = self.lookup_class_path(scope, &parts);
                        // A replaceable class's constraining modifiers (and, when it
                        // was redeclared, a check that the new class fits).
                        let mut unconstrained = true;
                        if let Some(Found::Class(c)) = found {
                            if let Some(cmod) = self.class_constraint(scope, &parts, c, d.span) {
                                merged = merged.over_into(cmod);
                                unconstrained = false;
                            }
                        }
                        if cacheable {
                            self.clause_types.insert(key, (found, unconstrained));
                        }
                        found
                    }
                }
            }
        };
        let Some(found) = found else {
            // The name check covers the flattened class and its nested classes; a type
            // unknown in a class used from elsewhere (a record, a library model) is
            // reported here (`flatten` drops the repeat of one already reported).
            let d = crate::resolve::unknown_name(self.tree, scope.class, &cc.type_name, "type");
            self.diags.push(d);
            return;
        };
        let Some((kind, merged, short_dims)) = self.resolve_type_dims(found, merged) else {
            return;
        };
        let variability = match cc.prefix.variability {
            Some(unimo_syntax::ast::Variability::Constant) => Some(Variability::Constant),
            Some(unimo_syntax::ast::Variability::Parameter) => Some(Variability::Parameter),
            Some(unimo_syntax::ast::Variability::Discrete) => Some(Variability::Discrete),
            None => inherited,
        };
        let mut dims = Vec::new();
        // `Real[3] x[2]` is `Real x[2, 3]` (spec 10.1): the name's dimensions come first.
        for s in d.dims.iter().chain(&cc.type_dims) {
            match s {
                Subscript::Expr(e) => {
                    if let Some(n) = self.dimension(e, scope) {
                        dims.push(n);
                    }
                }
                Subscript::Colon(span) => {
                    // `[:]`: the size comes from the binding.
                    // Its value when it is constant; else its shape, which a binding
                    // of variables (`reset = {b1.on, b2.on}`) has too.
                    let mut refused = None;
                    let size = merged.binding.clone().and_then(|b| {
                        let flat = self.expr(&b.expr, &b.scope, &mut Vec::new(), &mut Vec::new());
                        match eval::eval(&flat, self, &mut Vec::new()) {
                            Ok(v) => Some(v.dims()),
                            Err(e) => {
                                if let EvalError::Unsupported { what, .. } = e {
                                    refused = Some(what);
                                }
                                self.shape_of(&flat)
                            }
                        }
                    });
                    match size {
                        Some(vd) if vd.len() > dims.len() => dims.push(vd[dims.len()]),
                        _ => {
                            let mut d = Diagnostic::error(
                                "E2003",
                                "the size of `[:]` must follow from a constant binding",
                            )
                            .at(*span, "unknown size");
                            if let Some(what) = refused {
                                d = d.with_note(format!("its binding cannot be evaluated: {what}"));
                            }
                            self.diags.push(d);
                        }
                    }
                }
            }
        }
        for (sub, dim_scope) in &short_dims {
            if let Subscript::Expr(e) = sub {
                if let Some(n) = self.dimension(e, dim_scope) {
                    dims.push(n);
                }
            }
        }
        let count = dims
            .iter()
            .try_fold(1usize, |acc, &n| acc.checked_mul(n))
            .unwrap_or(usize::MAX);
        if !self.spend(count, d.span) {
            return;
        }
        match kind {
            Kind::Builtin(ty) => {
                let var = self.builtin_var(key, ty, &merged, cc, d, variability, dims, top);
                self.model.vars.push(var);
            }
            Kind::Class(c) => {
                // An instance of a partial class (spec 4.7; an `outer` component is
                // not instantiated here, it refers to its inner).
                if self.tree.get(c).def.partial {
                    let class_name = self.tree.full_name(c);
                    self.diags.push(
                        Diagnostic::error(
                            "E2009",
                            format!(
                                "component `{key}` is an instance of the partial class \
                                 `{class_name}`"
                            ),
                        )
                        .at(d.name.span, "instance of a partial class")
                        .with_label(self.tree.get(c).def.name.span, "declared `partial` here")
                        .with_help(
                            "use a class that extends it, or redeclare the component with one",
                        ),
                    );
                    return;
                }
                let mut path = Vec::with_capacity(scope.prefix.len() + 1);
                path.extend_from_slice(&scope.prefix);
                path.push(part(name, d.name.span));
                let record = self.is_record(c);
                // A record binding is split into field bindings where it can be
                // (per element of an array of records).
                let merged = if record && dims.is_empty() {
                    self.note_record_instance(&key, c);
                    self.split_record_binding(c, merged)
                } else {
                    merged
                };
                // An array of records is bound element by element when its binding
                // can be taken apart (an array of constructor calls, a record array).
                let per_element = record
                    && !dims.is_empty()
                    && merged.binding.as_ref().is_some_and(|b| {
                        let first = vec![1; dims.len()];
                        self.pick_element(&b.expr, &b.scope, &first).is_some()
                    });
                // A binding of a structured component left whole is a record equation.
                if !per_element {
                    self.record_binding_equation(&merged, &path, variability, &key, d.span);
                }
                // `input`/`output` on a structured component applies to its variables;
                // those of the top-level model's connectors are the model's interface.
                let saved = self.inherited_causality;
                self.inherited_causality = cc.prefix.causality.or(saved);
                if self.tree.get(c).def.prefixes.expandable {
                    self.expandable.push(key.clone());
                }
                let top = top && self.tree.get(c).def.kind == ClassKind::Connector;
                if dims.is_empty() {
                    self.class_body(c, &path, &merged, variability, top);
                } else {
                    for t in index_tuples(&dims) {
                        let mut p = path.clone();
                        if let Some(last) = p.last_mut() {
                            last.subscripts = t
                                .iter()
                                .map(|i| Subscript::Expr(int_expr(*i, d.span)))
                                .collect();
                        }
                        // A modifier without `each` gives element t its part of the
                        // array value (spec 7.2.5).
                        let mut element = self.element_mod(&merged, &t);
                        if record {
                            let key = instance_key(&p);
                            self.note_record_instance(&key, c);
                            element.binding = if per_element {
                                merged.binding.as_ref().and_then(|b| {
                                    let e = self.pick_element(&b.expr, &b.scope, &t)?;
                                    Some(Bound {
                                        expr: e,
                                        scope: b.scope.clone(),
                                    })
                                })
                            } else {
                                None
                            };
                            element = self.split_record_binding(c, element);
                            self.record_binding_equation(&element, &p, variability, &key, d.span);
                        }
                        self.class_body(c, &p, &element, variability, top);
                    }
                }
                self.inherited_causality = saved;
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn builtin_var(
        &mut self,
        name: String,
        ty: FlatType,
        m: &Mod,
        cc: &ComponentClause,
        d: &ComponentDecl,
        variability: Option<Variability>,
        dims: Vec<usize>,
        top: bool,
    ) -> FlatVar {
        let mut attributes = Vec::new();
        let mut each_attributes = Vec::new();
        for (attr, am) in &m.children {
            if !ATTRIBUTES.contains(&attr.as_str()) {
                let span = am.binding.as_ref().map_or(d.span, |b| b.expr.span);
                self.diags.push(
                    Diagnostic::error("E2004", format!("`{attr}` is not an attribute of `{name}`"))
                        .at(span, "value given here")
                        .with_help(format!(
                            "attributes of predefined types: {}",
                            ATTRIBUTES.join(", ")
                        )),
                );
                continue;
            }
            if let Some(b) = &am.binding {
                attributes.push((
                    attr.clone(),
                    self.expr(&b.expr, &b.scope, &mut Vec::new(), &mut Vec::new()),
                ));
                if am.each {
                    each_attributes.push(attr.clone());
                }
            }
        }
        let binding = m
            .binding
            .as_ref()
            .map(|b: &Bound| self.expr(&b.expr, &b.scope, &mut Vec::new(), &mut Vec::new()));
        let discrete_type = matches!(
            ty,
            FlatType::Integer | FlatType::Boolean | FlatType::String | FlatType::Enumeration { .. }
        );
        let variability = match variability {
            Some(v) => v,
            None if discrete_type => Variability::Discrete,
            None => Variability::Continuous,
        };
        FlatVar {
            name,
            ty,
            variability,
            causality: cc.prefix.causality.or(self.inherited_causality),
            flow: cc.prefix.connection == Some(Connection::Flow),
            dims,
            binding: binding.map(Box::new),
            attributes,
            each_attributes,
            description: d.comment.description.clone(),
            top_level: top,
            evaluate: annotation_is_true(d.comment.annotation.as_ref(), "Evaluate"),
            is_final: std::mem::take(&mut self.element_final) || m.is_final,
            origin: d.span,
        }
    }

    // ------------------------------------------------------------ equations

    fn equation(
        &mut self,
        eq: &Equation,
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        out: &mut Vec<Equation>,
    ) {
        let kind = match &eq.kind {
            EquationKind::Simple { lhs, rhs } => EquationKind::Simple {
                lhs: self.expr(lhs, scope, iters, &mut Vec::new()),
                rhs: self.expr(rhs, scope, iters, &mut Vec::new()),
            },
            EquationKind::Call(c) => {
                EquationKind::Call(self.expr(c, scope, iters, &mut Vec::new()))
            }
            EquationKind::Connect { a, b } => {
                let fa = self.cref(a, scope, iters, &mut Vec::new());
                let fb = self.cref(b, scope, iters, &mut Vec::new());
                self.connects.push(Connect {
                    a: fa,
                    b: fb,
                    a_outside: a.parts.len() == 1,
                    b_outside: b.parts.len() == 1,
                    span: eq.span,
                });
                return;
            }
            EquationKind::For { indices, body } => {
                self.for_equation(indices, body, scope, iters, out);
                return;
            }
            EquationKind::If {
                branches,
                otherwise,
            } => {
                // Decided now when every condition is a parameter expression.
                // Some(Some(k)): branch k is taken; Some(None): all conditions false;
                // None: a condition is not a parameter expression.
                let mut decided = Some(None);
                for (k, (c, _)) in branches.iter().enumerate() {
                    let flat = self.expr(c, scope, iters, &mut Vec::new());
                    match eval::eval(&flat, self, iters) {
                        Ok(Value::Bool(true)) => {
                            decided = Some(Some(k));
                            break;
                        }
                        Ok(Value::Bool(false)) => {}
                        _ => {
                            decided = None;
                            break;
                        }
                    }
                }
                let all_false = decided == Some(None);
                let decided = decided.flatten();
                if let Some(k) = decided {
                    for e in &branches[k].1 {
                        self.equation(e, scope, iters, out);
                    }
                    return;
                }
                if all_false {
                    for e in otherwise {
                        self.equation(e, scope, iters, out);
                    }
                    return;
                }
                let fb = self.equation_branches(branches, scope, iters);
                let mut fo = Vec::new();
                for e in otherwise {
                    self.equation(e, scope, iters, &mut fo);
                }
                EquationKind::If {
                    branches: fb,
                    otherwise: fo,
                }
            }
            EquationKind::When { branches } => EquationKind::When {
                branches: self.equation_branches(branches, scope, iters),
            },
        };
        out.push(Equation {
            kind,
            comment: Comment::default(),
            span: eq.span,
        });
    }

    /// The branches of an `if` or `when` equation, conditions and bodies flattened.
    fn equation_branches(
        &mut self,
        branches: &[(Expr, Vec<Equation>)],
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
    ) -> Vec<(Expr, Vec<Equation>)> {
        let mut out = Vec::new();
        for (c, body) in branches {
            let cond = self.expr(c, scope, iters, &mut Vec::new());
            let mut b = Vec::new();
            for e in body {
                self.equation(e, scope, iters, &mut b);
            }
            out.push((cond, b));
        }
        out
    }

    fn for_equation(
        &mut self,
        indices: &[ForIndex],
        body: &[Equation],
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        out: &mut Vec<Equation>,
    ) {
        let Some((first, rest)) = indices.split_first() else {
            for e in body {
                self.equation(e, scope, iters, out);
            }
            return;
        };
        let Some(range) = &first.range else {
            self.error(
                "E2003",
                "a `for` equation needs an explicit range here".into(),
                first.name.span,
                "no range",
            );
            return;
        };
        let flat = self.expr(range, scope, iters, &mut Vec::new());
        let values = match eval::eval(&flat, self, iters) {
            Ok(Value::Array(v)) => v,
            Ok(_) => {
                self.error(
                    "E2003",
                    "a `for` range must be an array".into(),
                    range.span,
                    "not an array",
                );
                return;
            }
            Err(e) => {
                self.eval_error(e, "`for` range");
                return;
            }
        };
        for v in values {
            if !self.spend(body.len().max(1), first.name.span) {
                return;
            }
            iters.push((first.name.text.to_string(), v));
            self.for_equation(rest, body, scope, iters, out);
            iters.pop();
        }
    }

    /// A statement of a model's algorithm: like [`Self::statement`], but a `for` loop
    /// whose range is a parameter expression is unrolled (its index becomes a value),
    /// so that a loop over a component array (`InPorts[i].F`) names the scalarized
    /// components, which the flat model has, and not `InPorts[i]`, which it has not.
    /// Loops with `break` or `return` stay loops.
    fn model_statements(
        &mut self,
        stmts: &[Statement],
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        out: &mut Vec<Statement>,
    ) {
        for st in stmts {
            match &st.kind {
                StatementKind::For { indices, body }
                    if indices.len() == 1 && !breaks(body) && indices[0].range.is_some() =>
                {
                    let range = indices[0].range.as_ref().unwrap();
                    let flat = self.expr(range, scope, iters, &mut Vec::new());
                    if let Ok(Value::Array(values)) = eval::eval(&flat, self, iters) {
                        for v in values {
                            iters.push((indices[0].name.text.to_string(), v));
                            self.model_statements(body, scope, iters, out);
                            iters.pop();
                        }
                    } else {
                        out.push(self.statement_in(st, scope, iters, &mut Vec::new(), true));
                    }
                }
                _ => out.push(self.statement_in(st, scope, iters, &mut Vec::new(), true)),
            }
        }
    }

    fn statement(&mut self, st: &Statement, scope: &Scope, locals: &mut Vec<String>) -> Statement {
        self.statement_in(st, scope, &mut Vec::new(), locals, false)
    }

    fn statement_in(
        &mut self,
        st: &Statement,
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
        unroll: bool,
    ) -> Statement {
        let body = |this: &mut Self,
                    b: &[Statement],
                    iters: &mut Vec<(String, Value)>,
                    locals: &mut Vec<String>|
         -> Vec<Statement> {
            if unroll && locals.is_empty() {
                let mut out = Vec::new();
                this.model_statements(b, scope, iters, &mut out);
                out
            } else {
                b.iter()
                    .map(|s| this.statement_in(s, scope, iters, locals, unroll))
                    .collect()
            }
        };
        // `if`/`when` branches: each condition, then its body.
        let guarded = |this: &mut Self,
                       branches: &[(Expr, Vec<Statement>)],
                       iters: &mut Vec<(String, Value)>,
                       locals: &mut Vec<String>|
         -> Vec<(Expr, Vec<Statement>)> {
            branches
                .iter()
                .map(|(c, b)| {
                    (
                        this.expr(c, scope, iters, locals),
                        body(this, b, iters, locals),
                    )
                })
                .collect()
        };
        let kind = match &st.kind {
            StatementKind::Assign { target, value } => StatementKind::Assign {
                target: self.cref(target, scope, iters, locals),
                value: self.expr(value, scope, iters, locals),
            },
            StatementKind::MultiAssign { targets, value } => StatementKind::MultiAssign {
                targets: targets
                    .iter()
                    .map(|t| t.as_ref().map(|e| self.expr(e, scope, iters, locals)))
                    .collect(),
                value: self.expr(value, scope, iters, locals),
            },
            StatementKind::Call(e) => StatementKind::Call(self.expr(e, scope, iters, locals)),
            StatementKind::If {
                branches,
                otherwise,
            } => StatementKind::If {
                branches: guarded(self, branches, iters, locals),
                otherwise: body(self, otherwise, iters, locals),
            },
            StatementKind::For { indices, body: b } => {
                let indices = self.indices(indices, scope, iters, locals);
                let n = indices.len();
                locals.extend(indices.iter().map(|i| i.name.text.to_string()));
                let b = b
                    .iter()
                    .map(|s| self.statement_in(s, scope, iters, locals, unroll))
                    .collect();
                locals.truncate(locals.len() - n);
                StatementKind::For { indices, body: b }
            }
            StatementKind::While { condition, body: b } => StatementKind::While {
                condition: self.expr(condition, scope, iters, locals),
                body: b
                    .iter()
                    .map(|s| self.statement_in(s, scope, iters, locals, unroll))
                    .collect(),
            },
            StatementKind::When { branches } => StatementKind::When {
                branches: guarded(self, branches, iters, locals),
            },
            StatementKind::Return => StatementKind::Return,
            StatementKind::Break => StatementKind::Break,
        };
        Statement {
            kind,
            comment: Comment::default(),
            span: st.span,
        }
    }

    // ------------------------------------------------------------ expressions

    /// A reference made absolute: the instance prefix added to a component of the
    /// scope; `for` indices replaced by their value; package constants inlined.
    fn cref(
        &mut self,
        r: &ComponentRef,
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
    ) -> ComponentRef {
        let Some(first) = r.parts.first().map(|p| p.name.text.clone()) else {
            return r.clone();
        };
        let plain = r.global || first == "time" || locals.iter().any(|l| *l == first);
        let component = !plain && self.tree.has_component(scope.class, &first);
        // A component reference gets the instance prefix (unless it goes through an
        // `outer`, below): the prefix is written first, then the parts as written.
        let direct = component && self.outer_alias.is_empty();
        let mut parts: Vec<RefPart> =
            Vec::with_capacity(if direct { scope.prefix.len() } else { 0 } + r.parts.len());
        if direct {
            parts.extend_from_slice(&scope.prefix);
        }
        for p in &r.parts {
            let mut subscripts = p.subscripts.clone();
            for s in &mut subscripts {
                if let Subscript::Expr(e) = s {
                    *e = self.expr(e, scope, iters, locals);
                    // Constant subscripts are folded (`x[i + 1]` in an unrolled loop is
                    // `x[3]`), so that every reference to an element looks the same.
                    if !matches!(e.kind, ExprKind::Integer(_) | ExprKind::End) && locals.is_empty()
                    {
                        if let Ok(Value::Int(k)) = eval::eval(e, self, &mut Vec::new()) {
                            *e = int_expr(k, e.span);
                        }
                    }
                }
            }
            parts.push(RefPart {
                name: p.name.clone(),
                subscripts,
            });
        }
        let r = ComponentRef {
            global: r.global,
            parts,
            span: r.span,
        };
        if plain || direct {
            return r;
        }
        if component {
            // A reference through an `outer` component goes to its `inner`.
            let mut head = scope.prefix.to_vec();
            head.push(r.parts[0].clone());
            let parts = match self.outer_alias.get(&instance_key_no_subs(&head)) {
                Some(inner) => {
                    let mut p = inner.clone();
                    if let Some(last) = p.last_mut() {
                        if !r.parts[0].subscripts.is_empty() {
                            last.subscripts = r.parts[0].subscripts.clone();
                        }
                    }
                    p.extend(r.parts.into_iter().skip(1));
                    p
                }
                None => {
                    head.extend(r.parts.into_iter().skip(1));
                    head
                }
            };
            return ComponentRef {
                global: false,
                parts,
                span: r.span,
            };
        }
        // A class path: an enumeration literal or a package constant, made global.
        let names: Vec<&str> = r.parts.iter().map(|p| p.name.text.as_str()).collect();
        let owner = match self.tree.lookup_simple(Some(scope.class), &first, false) {
            Some(Found::Class(c)) => Some(c),
            Some(Found::Component(c)) => Some(c),
            _ => None,
        };
        if let Some(owner) = owner {
            let full = match self.tree.lookup_dotted(Some(scope.class), &names, false) {
                Some(Found::Component(c)) => {
                    let mut n = self.tree.full_name(c);
                    n.push('.');
                    n.push_str(names.last().copied().unwrap_or(""));
                    n
                }
                Some(Found::Class(c)) => self.tree.full_name(c),
                _ => {
                    let _ = owner;
                    return r;
                }
            };
            let mut parts: Vec<RefPart> = crate::flat::split_name(&full)
                .into_iter()
                .map(|p| part(p, r.span))
                .collect();
            if let (Some(last), Some(orig)) = (parts.last_mut(), r.parts.last()) {
                last.subscripts = orig.subscripts.clone();
            }
            return ComponentRef {
                global: true,
                parts,
                span: r.span,
            };
        }
        r
    }

    /// `e` flattened in `scope`, outside any loop.
    pub(crate) fn flat_expr(&mut self, e: &Expr, scope: &Scope) -> Expr {
        self.expr(e, scope, &mut Vec::new(), &mut Vec::new())
    }

    pub(crate) fn expr(
        &mut self,
        e: &Expr,
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
    ) -> Expr {
        let span = e.span;
        let kind = match &e.kind {
            ExprKind::Ref(r) => {
                if r.parts.len() == 1 && !r.global {
                    let n = r.parts[0].name.text.as_str();
                    if !locals.iter().any(|l| l == n) {
                        if let Some((_, v)) = iters.iter().rev().find(|(k, _)| k == n) {
                            return v.to_expr(span);
                        }
                    }
                }
                if let Some(v) = self.redeclared_constant(r, scope, locals) {
                    return v;
                }
                let fr = self.cref(r, scope, iters, locals);
                if fr.global {
                    if let Some(v) = self.package_constant(&fr) {
                        return v;
                    }
                }
                ExprKind::Ref(fr)
            }
            ExprKind::Call { func, args } => {
                // `.asin(u)` names the built-in from the global scope.
                let simple = func.parts.len() == 1;
                if simple && func.parts[0].text == "getInstanceName" && args.positional.is_empty() {
                    return instance_name(&self.model.name, &scope.prefix, span);
                }
                let func = if simple && is_builtin_function(&func.parts[0].text) {
                    Name {
                        global: false,
                        ..func.clone()
                    }
                } else {
                    let parts: Vec<&str> = func.parts.iter().map(|p| p.text.as_str()).collect();
                    let found = if func.global {
                        self.tree.lookup_dotted(None, &parts, false)
                    } else {
                        self.lookup_class_path(scope, &parts)
                    };
                    match found {
                        Some(Found::Class(c)) => {
                            let c = self.real_class(c);
                            let def = self.tree.get(c).def.clone();
                            let builtin = crate::external::builtin_alias(&def);
                            let full = match builtin {
                                Some(b) => b.to_owned(),
                                // `Table(...)` of an external object class calls its
                                // constructor.
                                None if crate::external::is_external_object(&def) => {
                                    format!("{}.constructor", self.tree.full_name(c))
                                }
                                None => self.tree.full_name(c),
                            };
                            Name {
                                global: builtin.is_none(),
                                parts: crate::flat::split_name(&full)
                                    .into_iter()
                                    .map(|p| Ident {
                                        text: p.into(),
                                        span: func.span,
                                    })
                                    .collect(),
                                span: func.span,
                            }
                        }
                        _ => func.clone(),
                    }
                };
                // A reduction over component array elements (`sum(c[i].f for i in
                // 1:n)`) is written out: `sum({c[1].f, c[2].f, ...})`.
                if let (Some(body), true) = (args.positional.first(), args.positional.len() == 1) {
                    if let Some(items) = self.unroll(body, &args.iterators, scope, iters, locals) {
                        return Expr {
                            kind: ExprKind::Call {
                                func,
                                args: Box::new(CallArgs {
                                    positional: vec![Expr {
                                        kind: ExprKind::Array(items),
                                        span,
                                    }],
                                    named: Vec::new(),
                                    iterators: Vec::new(),
                                    span: args.span,
                                }),
                            },
                            span,
                        };
                    }
                }
                let n = args.iterators.len();
                let iterators = self.indices(&args.iterators, scope, iters, locals);
                locals.extend(iterators.iter().map(|i| i.name.text.to_string()));
                let positional = args
                    .positional
                    .iter()
                    .map(|a| self.expr(a, scope, iters, locals))
                    .collect();
                let named = args
                    .named
                    .iter()
                    .map(|a| NamedArg {
                        name: a.name.clone(),
                        value: self.expr(&a.value, scope, iters, locals),
                    })
                    .collect();
                locals.truncate(locals.len() - n);
                ExprKind::Call {
                    func,
                    args: Box::new(CallArgs {
                        positional,
                        named,
                        iterators,
                        span: args.span,
                    }),
                }
            }
            ExprKind::Comprehension { body, indices } => {
                if let Some(items) = self.unroll(body, indices, scope, iters, locals) {
                    return Expr {
                        kind: ExprKind::Array(items),
                        span,
                    };
                }
                let indices = self.indices(indices, scope, iters, locals);
                let n = indices.len();
                locals.extend(indices.iter().map(|i| i.name.text.to_string()));
                let body = Box::new(self.expr(body, scope, iters, locals));
                locals.truncate(locals.len() - n);
                ExprKind::Comprehension { body, indices }
            }
            ExprKind::Unary { op, operand } => ExprKind::Unary {
                op: *op,
                operand: Box::new(self.expr(operand, scope, iters, locals)),
            },
            ExprKind::Binary { op, lhs, rhs } => ExprKind::Binary {
                op: *op,
                lhs: Box::new(self.expr(lhs, scope, iters, locals)),
                rhs: Box::new(self.expr(rhs, scope, iters, locals)),
            },
            ExprKind::If {
                branches,
                otherwise,
            } => ExprKind::If {
                branches: branches
                    .iter()
                    .map(|(c, v)| {
                        (
                            self.expr(c, scope, iters, locals),
                            self.expr(v, scope, iters, locals),
                        )
                    })
                    .collect(),
                otherwise: Box::new(self.expr(otherwise, scope, iters, locals)),
            },
            ExprKind::Range { start, step, stop } => ExprKind::Range {
                start: Box::new(self.expr(start, scope, iters, locals)),
                step: step
                    .as_ref()
                    .map(|s| Box::new(self.expr(s, scope, iters, locals))),
                stop: Box::new(self.expr(stop, scope, iters, locals)),
            },
            ExprKind::Array(items) => ExprKind::Array(
                items
                    .iter()
                    .map(|i| self.expr(i, scope, iters, locals))
                    .collect(),
            ),
            ExprKind::Matrix(rows) => ExprKind::Matrix(
                rows.iter()
                    .map(|r| {
                        r.iter()
                            .map(|i| self.expr(i, scope, iters, locals))
                            .collect()
                    })
                    .collect(),
            ),
            ExprKind::Tuple(items) => ExprKind::Tuple(
                items
                    .iter()
                    .map(|i| i.as_ref().map(|e| self.expr(e, scope, iters, locals)))
                    .collect(),
            ),
            other => other.clone(),
        };
        Expr { kind, span }
    }

    /// The elements of a one-iterator comprehension whose body selects components by
    /// the iterator (`{coil[i].r[3] for i in 1:n}`), when its range is known: a flat
    /// model has `coil[1].r`, not `coil[i].r`.
    fn unroll(
        &mut self,
        body: &Expr,
        indices: &[ForIndex],
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
    ) -> Option<Vec<Expr>> {
        let [index] = indices else {
            return None;
        };
        let name = index.name.text.as_str();
        let mut selects = false;
        crate::flat::for_each_ref(body, &mut |r| {
            let n = r.parts.len();
            for p in &r.parts[..n.saturating_sub(1)] {
                for sub in &p.subscripts {
                    if let Subscript::Expr(e) = sub {
                        let mut uses = false;
                        crate::flat::for_each_ref(e, &mut |x| {
                            uses |= x.parts.len() == 1 && x.parts[0].name.text == name;
                        });
                        selects |= uses;
                    }
                }
            }
        });
        if !selects {
            return None;
        }
        let range = self.expr(index.range.as_ref()?, scope, iters, locals);
        let Ok(Value::Array(values)) = eval::eval(&range, self, iters) else {
            return None;
        };
        let mut items = Vec::with_capacity(values.len());
        for v in values {
            iters.push((name.to_owned(), v));
            items.push(self.expr(body, scope, iters, locals));
            iters.pop();
        }
        Some(items)
    }

    /// `for` indices with their ranges made absolute (the names stay local).
    fn indices(
        &mut self,
        indices: &[ForIndex],
        scope: &Scope,
        iters: &mut Vec<(String, Value)>,
        locals: &mut Vec<String>,
    ) -> Vec<ForIndex> {
        indices
            .iter()
            .map(|i| ForIndex {
                name: i.name.clone(),
                range: i.range.as_ref().map(|r| {
                    let flat = self.expr(r, scope, iters, locals);
                    // A range of a function's inputs or locals stays as written.
                    let mut local = false;
                    crate::flat::for_each_ref(&flat, &mut |r| {
                        local |= !r.global
                            && r.parts
                                .first()
                                .is_some_and(|p| locals.iter().any(|l| *l == p.name.text))
                    });
                    if local {
                        return flat;
                    }
                    // A range of parameters is decided here, so that the flat text
                    // names no structural parameter (they are folded away).
                    match eval::eval(&flat, self, iters) {
                        Ok(v @ Value::Array(_)) => v.to_expr(r.span),
                        _ => flat,
                    }
                }),
            })
            .collect()
    }

    /// The value of a package constant (`Modelica.Constants.pi`), as a literal.
    fn package_constant(&mut self, r: &ComponentRef) -> Option<Expr> {
        let names: Vec<&str> = r.parts.iter().map(|p| p.name.text.as_str()).collect();
        let (last, owner_path) = names.split_last()?;
        let Some(Found::Class(owner)) = self.tree.lookup_dotted(None, owner_path, false) else {
            return None;
        };
        let (binding, scope) = self.class_constant(owner, last, 0)?;
        let flat = self.expr(&binding, &scope, &mut Vec::new(), &mut Vec::new());
        let v = eval::eval(&flat, self, &mut Vec::new()).ok()?;
        let subs = r
            .parts
            .last()
            .map(|p| p.subscripts.clone())
            .unwrap_or_default();
        if subs.is_empty() {
            Some(v.to_expr(r.span))
        } else {
            None
        }
    }

    /// The value of constant `name` of class `owner`: declared there, or inherited,
    /// with the modifiers of short class definitions and `extends` clauses on the way
    /// (`package Water extends PartialMedium(cp = 4184)`, `package M = Water`).
    pub(crate) fn class_constant(
        &mut self,
        owner: ClassId,
        name: &str,
        depth: usize,
    ) -> Option<(Expr, Scope)> {
        if depth > MAX_DEPTH {
            return None;
        }
        let def = self.tree.get(owner).def.clone();
        let here = Scope {
            class: owner,
            prefix: std::sync::Arc::from([]),
        };
        let modified = |cm: &Option<ClassModification>| -> Option<Expr> {
            cm.iter().flat_map(|m| &m.args).find_map(|a| match a {
                Argument::Modify {
                    name: n,
                    modification: Some(m),
                    ..
                } if n.parts.len() == 1 && n.parts[0].text == name => m.binding.clone(),
                _ => None,
            })
        };
        match &def.body {
            ClassBody::Short { modification, .. } => {
                // The modifier of a short class is written in its enclosing scope.
                if let Some(b) = modified(modification) {
                    let scope = Scope {
                        class: self.tree.get(owner).parent.unwrap_or(owner),
                        prefix: std::sync::Arc::from([]),
                    };
                    return Some((b, scope));
                }
                let base = self.tree.bases(owner).first().copied()?;
                self.class_constant(base, name, depth + 1)
            }
            ClassBody::Long {
                composition,
                extends: class_extends,
                ..
            } => {
                for e in &composition.elements {
                    if let ElementKind::Component(cc) = &e.kind {
                        if let Some(d) = cc.components.iter().find(|d| d.name.text == name) {
                            if cc.prefix.variability
                                != Some(unimo_syntax::ast::Variability::Constant)
                            {
                                return None;
                            }
                            let b = d.modification.as_ref()?.binding.clone()?;
                            return Some((b, here));
                        }
                    }
                }
                // The bases in `bases` order: a class extension's original first.
                let extends: Vec<Option<ClassModification>> = class_extends
                    .iter()
                    .map(|x| x.modification.clone())
                    .chain(composition.elements.iter().filter_map(|e| match &e.kind {
                        ElementKind::Extends(x) => Some(x.modification.clone()),
                        _ => None,
                    }))
                    .collect();
                let bases = self.tree.bases(owner);
                for (base, m) in bases.into_iter().zip(extends) {
                    if !self.tree.has_component(base, name) {
                        continue;
                    }
                    if let Some(b) = modified(&m) {
                        return Some((b, here));
                    }
                    return self.class_constant(base, name, depth + 1);
                }
                None
            }
            ClassBody::Enumeration { .. } | ClassBody::Der { .. } => None,
        }
    }
}

impl Instantiator<'_, '_> {
    /// An array dimension evaluated at compile time (`E2003` when it is not a
    /// non-negative Integer).
    fn dimension(&mut self, e: &Expr, scope: &Scope) -> Option<usize> {
        let flat = self.expr(e, scope, &mut Vec::new(), &mut Vec::new());
        match eval::eval(&flat, self, &mut Vec::new()).map(|v| v.as_int()) {
            Ok(Some(n)) if n >= 0 => Some(n as usize),
            Ok(_) => {
                self.error(
                    "E2003",
                    "an array dimension must be a non-negative Integer".into(),
                    e.span,
                    "here",
                );
                None
            }
            Err(err) => {
                self.eval_error(err, "array dimension");
                None
            }
        }
    }

    /// The modification of element `index` of a component array: the bindings of
    /// modifiers without `each` are subscripted (a literal array gives its element, a
    /// reference gets the subscripts, a constant is evaluated and picked).
    fn element_mod(&mut self, m: &Mod, index: &[i64]) -> Mod {
        let mut out = m.clone();
        out.children = m
            .children
            .iter()
            .map(|(n, c)| (n.clone(), self.element_child(c, index)))
            .collect();
        out
    }

    fn element_child(&mut self, m: &Mod, index: &[i64]) -> Mod {
        if m.each {
            return m.clone();
        }
        let mut out = m.clone();
        if let Some(b) = &m.binding {
            if let Some(e) = self.pick_element(&b.expr, &b.scope, index) {
                out.binding = Some(crate::modif::Bound {
                    expr: e,
                    scope: b.scope.clone(),
                });
            }
        }
        out.children = m
            .children
            .iter()
            .map(|(n, c)| (n.clone(), self.element_child(c, index)))
            .collect();
        out
    }

    pub(crate) fn pick_element(&mut self, e: &Expr, scope: &Scope, index: &[i64]) -> Option<Expr> {
        let Some((&first, rest)) = index.split_first() else {
            return Some(e.clone());
        };
        match &e.kind {
            ExprKind::Array(items) => {
                let item = items.get(usize::try_from(first - 1).ok()?)?;
                self.pick_element(item, scope, rest)
            }
            ExprKind::Ref(r) => {
                // Subscripted only when it names an array: a parameter array is
                // evaluated, a variable is looked up; a scalar is left as it is.
                let flat = self.expr(e, scope, &mut Vec::new(), &mut Vec::new());
                if let Ok(v) = eval::eval(&flat, self, &mut Vec::new()) {
                    return self.pick_value(v, index, e.span);
                }
                let key = match &flat.kind {
                    ExprKind::Ref(fr) => eval::var_key(fr),
                    _ => return None,
                };
                let id = self.var_id(&key)?;
                if self.model.vars[id.0 as usize].dims.len() < index.len() {
                    return None;
                }
                let mut r = r.clone();
                let last = r.parts.last_mut()?;
                last.subscripts
                    .extend(index.iter().map(|&i| Subscript::Expr(int_expr(i, e.span))));
                Some(Expr {
                    kind: ExprKind::Ref(r),
                    span: e.span,
                })
            }
            _ => {
                // A constant array: evaluate it and pick the element.
                let flat = self.expr(e, scope, &mut Vec::new(), &mut Vec::new());
                if let Ok(v) = eval::eval(&flat, self, &mut Vec::new()) {
                    return self.pick_value(v, index, e.span);
                }
                // An element-wise expression of arrays that are not constant
                // (`u = us + ones(n)`): the element of each operand.
                let picked = |this: &mut Self, x: &Expr| this.pick_element(x, scope, index);
                let kind = match &e.kind {
                    ExprKind::Binary { op, lhs, rhs } => {
                        let elementwise = crate::lookup::is_elementwise(*op);
                        let (l, r) = (picked(self, lhs), picked(self, rhs));
                        match (l, r) {
                            (Some(l), Some(r)) if elementwise => ExprKind::Binary {
                                op: *op,
                                lhs: Box::new(l),
                                rhs: Box::new(r),
                            },
                            // An array scaled by a scalar.
                            (Some(l), None)
                                if elementwise || matches!(op, BinaryOp::Mul | BinaryOp::Div) =>
                            {
                                ExprKind::Binary {
                                    op: *op,
                                    lhs: Box::new(l),
                                    rhs: rhs.clone(),
                                }
                            }
                            (None, Some(r)) if elementwise || matches!(op, BinaryOp::Mul) => {
                                ExprKind::Binary {
                                    op: *op,
                                    lhs: lhs.clone(),
                                    rhs: Box::new(r),
                                }
                            }
                            _ => return None,
                        }
                    }
                    ExprKind::Unary { op, operand } => ExprKind::Unary {
                        op: *op,
                        operand: Box::new(picked(self, operand)?),
                    },
                    ExprKind::Call { func, args } => {
                        let x = picked(self, crate::lookup::elementwise_arg(func, args)?)?;
                        ExprKind::Call {
                            func: func.clone(),
                            args: Box::new(CallArgs {
                                positional: vec![x],
                                named: Vec::new(),
                                iterators: Vec::new(),
                                span: args.span,
                            }),
                        }
                    }
                    _ => return None,
                };
                Some(Expr { kind, span: e.span })
            }
        }
    }

    /// Element `index` of an array value; `None` for a scalar (left to broadcast).
    fn pick_value(&self, mut v: Value, index: &[i64], span: Span) -> Option<Expr> {
        for &i in index {
            v = match v {
                Value::Array(items) => items.into_iter().nth(usize::try_from(i - 1).ok()?)?,
                _ => return None,
            };
        }
        Some(v.to_expr(span))
    }

    /// An expression of a function body, with names resolved in the function's scope.
    pub(crate) fn expr_in_function(&mut self, e: &Expr, scope: &Scope) -> Expr {
        self.expr(e, scope, &mut Vec::new(), &mut Vec::new())
    }

    /// An expression of a function body, its formal parameters and locals kept local.
    pub(crate) fn function_expr(
        &mut self,
        e: &Expr,
        scope: &Scope,
        locals: &mut Vec<String>,
    ) -> Expr {
        self.expr(e, scope, &mut Vec::new(), locals)
    }

    /// A statement of a function body, its formal parameters and locals kept local.
    pub(crate) fn function_statement(
        &mut self,
        st: &Statement,
        scope: &Scope,
        locals: &mut Vec<String>,
    ) -> Statement {
        self.statement(st, scope, locals)
    }
}

impl Env for Instantiator<'_, '_> {
    fn dims(&mut self, key: &str) -> Option<Vec<usize>> {
        let id = self.var_id(key)?;
        Some(self.model.vars[id.0 as usize].dims.clone())
    }

    fn call(
        &mut self,
        name: &str,
        positional: Vec<Value>,
        named: Vec<(String, Value)>,
        span: Span,
    ) -> Result<Value, EvalError> {
        self.call_function(name, positional, named, span)
    }

    fn var(&mut self, key: &str, span: Span) -> Result<Value, EvalError> {
        if let Some(v) = self.values.get(key) {
            return Ok(v.clone());
        }
        let Some(id) = self.var_id(key) else {
            if let Some(v) = self.enum_literal(key) {
                return Ok(v);
            }
            if let Some(r) = self.pending_own_value(key, span) {
                return r;
            }
            return Err(EvalError::NotConstant {
                span,
                what: format!("`{key}`"),
            });
        };
        let var = self.model.vars[id.0 as usize].clone();
        if !matches!(
            var.variability,
            Variability::Parameter | Variability::Constant
        ) {
            return Err(EvalError::NotConstant {
                span,
                what: format!("the variable `{key}`"),
            });
        }
        let expr = var
            .binding
            .as_deref()
            .cloned()
            .or_else(|| {
                var.attributes
                    .iter()
                    .find(|(n, _)| n == "start")
                    .map(|(_, e)| e.clone())
            })
            .ok_or_else(|| EvalError::NotConstant {
                span,
                what: format!("`{key}`, a parameter without a value"),
            })?;
        if !self.evaluating.insert(key.to_owned()) {
            return Err(EvalError::Cycle {
                span,
                name: key.to_owned(),
            });
        }
        let r = eval::eval(&expr, self, &mut Vec::new());
        self.evaluating.remove(key);
        let v = r?;
        self.values.insert(key.to_owned(), v.clone());
        Ok(v)
    }
}

/// Whether a loop body leaves the loop early (`break`, `return`) at any depth.
fn breaks(body: &[Statement]) -> bool {
    body.iter().any(|s| match &s.kind {
        StatementKind::Break | StatementKind::Return => true,
        StatementKind::If {
            branches,
            otherwise,
        } => branches.iter().any(|(_, b)| breaks(b)) || breaks(otherwise),
        StatementKind::When { branches } => branches.iter().any(|(_, b)| breaks(b)),
        StatementKind::For { body, .. } | StatementKind::While { body, .. } => breaks(body),
        _ => false,
    })
}
