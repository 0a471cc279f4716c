//! Lowering: the flat model's variables become scalars, its (array) expressions become
//! scalar expressions in the arena (arrays are scalarized here), user functions are
//! inlined, and `der`, `pre`, `edge`, `change` and the other operators get their
//! meaning.

use crate::dae::*;
use crate::error::{DaeError, DaeResult};
use crate::expr::{ExprArena, ExprId, ScalarId};
use crate::tensor::{self, Tensor};
use rustc_hash::FxHashMap as HashMap;
use unimo_flat::functions::FlatFunction;
use unimo_flat::FlatModel;
use unimo_source::Span;
use unimo_syntax::ast::*;

mod array_builtins;
mod calls;
mod exprs;
mod references;
mod strings;
mod variables;

/// How deep user functions may call each other while being inlined.
pub(crate) const MAX_INLINE_DEPTH_PUB: usize = 32;

/// A name bound during lowering: a `for` iterator or a function's local.
#[derive(Clone, Debug)]
pub(crate) struct Local {
    pub name: String,
    pub value: Option<Tensor>,
    /// The record type of a function's record input, output or local: its value is
    /// the fields side by side (see `records.rs`).
    pub record: Option<String>,
    /// The value of a String input (`getInstanceName()`, a literal): Strings have no
    /// numeric value; only the functions unimo provides read them (a hash).
    pub text: Option<String>,
}

pub struct Lowerer<'m> {
    pub(crate) model: &'m FlatModel,
    pub(crate) dae: Dae,
    /// Flat variable name -> (first scalar, dims).
    pub(crate) vars: HashMap<String, (ScalarId, Vec<usize>)>,
    pub(crate) functions: HashMap<&'m str, &'m FlatFunction>,
    pub(crate) locals: Vec<Local>,
    /// Values of model variables assigned so far in the algorithm being lowered.
    pub(crate) assigned: Option<HashMap<ScalarId, ExprId>>,
    pub(crate) inline_depth: usize,
    /// Size of the dimension an `end` in a subscript refers to.
    pub(crate) end_stack: Vec<usize>,
    /// Actions collected while lowering the body of a `when`.
    pub(crate) when_actions: Option<Vec<(WhenAction, Span)>>,
    /// Values of parameters evaluated at compile time (NaN: not evaluable).
    pub(crate) params: crate::params::ParameterValues,
    /// Parameters fixed at translation (see `fold.rs`): equations read their values
    /// as constants.
    pub(crate) evaluated: HashMap<ScalarId, ExprId>,
    pub(crate) errors: Vec<DaeError>,
    /// Conditional `return`/`break` exits of the algorithm being executed.
    pub(crate) exits: Vec<crate::algo::Exit>,
    /// Instance paths that have variables inside (`a.port[2]` of `a.port[2].T`),
    /// built when a reference through an array of components first needs it.
    pub(crate) instances: Option<rustc_hash::FxHashSet<String>>,
    /// The impure random number generator's seeding and calls (`impure.rs`).
    pub(crate) impure: crate::impure::ImpureCalls,
    /// Real FFT sites lowered so far (`external_fft.rs`).
    pub(crate) fft_sites: usize,
}

pub(crate) fn unsupported(what: impl Into<String>, span: Span) -> DaeError {
    DaeError::Unsupported {
        what: what.into(),
        span,
    }
}

impl<'m> Lowerer<'m> {
    pub fn new(model: &'m FlatModel) -> Lowerer<'m> {
        Lowerer {
            model,
            dae: Dae {
                name: model.name.clone(),
                enumerations: model.enumerations.clone(),
                ..Dae::default()
            },
            vars: HashMap::default(),
            functions: model
                .functions
                .iter()
                .map(|f| (f.name.as_str(), f))
                .collect(),
            locals: Vec::new(),
            assigned: None,
            inline_depth: 0,
            end_stack: Vec::new(),
            when_actions: None,
            params: crate::params::ParameterValues::default(),
            evaluated: HashMap::default(),
            errors: Vec::new(),
            exits: Vec::new(),
            instances: None,
            impure: Default::default(),
            fft_sites: 0,
        }
    }

    /// The value of `e` when it is known at compile time: a constant, or an expression
    /// of parameters and constants whose bindings can be evaluated (structural
    /// parameters: sizes, ranges, indices, conditions of `if`-equations).
    /// The branch of an `if`-expression to lower alone: `Some` when its conditions
    /// are parameters known at compile time and lowering every branch fails (different
    /// sizes, or a value the back end does not have).
    fn structural_if<'e>(
        &mut self,
        branches: &'e [(Expr, Expr)],
        otherwise: &'e Expr,
    ) -> DaeResult<Option<&'e Expr>> {
        // Conditions known at compile time (parameters only, as for `if`-equations in
        // flattening): the branch taken, so that what the other branches hold never
        // reaches the structure (`y1 = if use_pder then der(y) else 0` with `use_pder`
        // false has no `der(y)`).
        for (c, v) in branches {
            let c = self.scalar(c)?;
            match self.const_value(c) {
                Some(x) if x != 0.0 => return Ok(Some(v)),
                Some(_) => continue,
                None => return Ok(None),
            }
        }
        Ok(Some(otherwise))
    }

    pub(crate) fn const_value(&mut self, e: ExprId) -> Option<f64> {
        self.params.of_expr(&self.dae, e)
    }

    /// A model variable in an expression: its value where it is fixed at translation.
    pub(crate) fn var_value(&mut self, s: ScalarId) -> ExprId {
        match self.evaluated.get(&s) {
            Some(&c) => c,
            None => self.dae.arena.var(s),
        }
    }

    /// The value of a parameter at translation (the one evaluator: `params.rs`).
    pub(crate) fn parameter_value(&mut self, s: ScalarId) -> Option<f64> {
        self.params.of_scalar(&self.dae, s)
    }

    pub(crate) fn a(&mut self) -> &mut ExprArena {
        &mut self.dae.arena
    }
}

/// `t` as an array of size `dims`: a scalar is repeated (`each`, or a scalar
/// attribute of an array).
pub(crate) fn broadcast(t: Tensor, dims: &[usize], span: Span) -> DaeResult<Tensor> {
    if t.dims == dims {
        return Ok(t);
    }
    let n: usize = dims.iter().product();
    if t.data.len() == 1 {
        return Ok(Tensor {
            dims: dims.to_vec(),
            data: vec![t.data[0]; n],
        });
    }
    if t.data.len() == n {
        return Ok(Tensor {
            dims: dims.to_vec(),
            data: t.data,
        });
    }
    Err(tensor::size_error(dims, &t.dims, span))
}

/// Every index tuple of an array of size `dims` in row-major order (1-based).
pub fn index_tuples(dims: &[usize]) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new()];
    for &d in dims {
        out = out
            .into_iter()
            .flat_map(|t| {
                (1..=d).map(move |i| {
                    let mut t = t.clone();
                    t.push(i);
                    t
                })
            })
            .collect();
    }
    out
}
