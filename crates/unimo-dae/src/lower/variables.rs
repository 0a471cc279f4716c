//! The flat model's variables as scalars: declared first, then their bindings and
//! attributes (start, fixed, nominal, min, max, stateSelect) once every name is known.

use super::{broadcast, index_tuples, Lowerer};
use crate::dae::*;
use crate::error::DaeCode;
use crate::error::DaeResult;
use crate::expr::ScalarId;
use unimo_flat::flat::{FlatType, FlatVar, Variability};
use unimo_syntax::ast::*;

impl Lowerer<'_> {
    /// Creates the scalars of every flat variable (attributes come later, when all
    /// names are known).
    pub(crate) fn declare_vars(&mut self) {
        for v in &self.model.vars {
            let ty = match &v.ty {
                FlatType::Real => ScalarType::Real,
                FlatType::Integer => ScalarType::Integer,
                FlatType::Boolean => ScalarType::Boolean,
                FlatType::String => continue,
                // A handle: the index of its object in `Dae::external_objects`.
                FlatType::ExternalObject { .. } => ScalarType::Integer,
                FlatType::Enumeration { name, .. } => {
                    let k = self
                        .dae
                        .enumerations
                        .iter()
                        .position(|(n, _)| n == name)
                        .unwrap_or(0);
                    ScalarType::Enumeration(k as u32)
                }
            };
            let kind = match v.variability {
                Variability::Constant => ScalarKind::Constant,
                Variability::Parameter => ScalarKind::Parameter,
                Variability::Discrete => ScalarKind::Discrete,
                Variability::Continuous if ty == ScalarType::Real => ScalarKind::Continuous,
                Variability::Continuous => ScalarKind::Discrete,
            };
            let first = ScalarId(self.dae.scalars.len() as u32);
            // A flat model read back names its variables `'body.r'`: results use the
            // name inside the quotes, as for the original model.
            let display = match v.name.strip_prefix('\'').and_then(|n| n.strip_suffix('\'')) {
                Some(inner) if !inner.is_empty() => inner.replace("\\'", "'"),
                _ => v.name.clone(),
            };
            for idx in index_tuples(&v.dims) {
                let name = if idx.is_empty() {
                    display.clone()
                } else {
                    format!(
                        "{}[{}]",
                        display,
                        idx.iter()
                            .map(|i| i.to_string())
                            .collect::<Vec<_>>()
                            .join(",")
                    )
                };
                let mut s = Scalar::new(name, kind, ty, v.origin);
                s.description = v.description.clone();
                s.input = v.top_level
                    && v.causality == Some(Causality::Input)
                    && kind != ScalarKind::Parameter;
                self.dae.add_scalar(s);
            }
            self.vars.insert(v.name.clone(), (first, v.dims.clone()));
        }
    }

    /// Lowers bindings and attributes; bindings of non-parameters become equations.
    pub(crate) fn var_attributes(&mut self) {
        // A parameter binding that needs another parameter's value declared further
        // down (`x_start[nx] = zeros(nx)` before `nx = size(a, 1) - 1`) is tried again
        // once the others are known.
        let mut deferred = Vec::new();
        for v in &self.model.vars {
            let Some(&(first, ref dims)) = self.vars.get(&v.name) else {
                continue;
            };
            let dims = dims.clone();
            let n = dims.iter().product::<usize>();
            if let Err(e) = self.var_binding(v, first, &dims) {
                let parameter = matches!(
                    v.variability,
                    Variability::Parameter | Variability::Constant
                );
                if parameter && e.code() == DaeCode::NotKnownAtCompileTime {
                    deferred.push((v, first, dims.clone(), e));
                } else {
                    self.errors.push(e);
                }
            }
            self.attributes_of(v, first, &dims, n);
        }
        while !deferred.is_empty() {
            self.params.forget_unknown();
            let before = deferred.len();
            let mut still = Vec::new();
            for (v, first, dims, _) in deferred {
                if let Err(e) = self.var_binding(v, first, &dims) {
                    still.push((v, first, dims, e));
                }
            }
            deferred = still;
            if deferred.len() == before {
                self.errors.extend(deferred.drain(..).map(|(.., e)| e));
            }
        }
    }

    /// A variable's binding: a parameter's value, or an equation.
    fn var_binding(&mut self, v: &FlatVar, first: ScalarId, dims: &[usize]) -> DaeResult<()> {
        if let Some(b) = &v.binding {
            let t = self.expr(b).and_then(|t| broadcast(t, dims, b.span))?;
            let parameter = matches!(
                v.variability,
                Variability::Parameter | Variability::Constant
            );
            for (k, &e) in t.data.iter().enumerate() {
                let s = ScalarId(first.0 + k as u32);
                if parameter {
                    self.dae.scalars[s.index()].binding = Some(e);
                } else {
                    let lhs = self.dae.arena.var(s);
                    self.dae.equations.push(crate::dae::Equation {
                        lhs,
                        rhs: e,
                        origin: b.span,
                        derivative_of: None,
                    });
                }
            }
        }
        Ok(())
    }

    /// A variable's attributes (`start`, `fixed`, `nominal`, ...).
    fn attributes_of(&mut self, v: &FlatVar, first: ScalarId, dims: &[usize], n: usize) {
        {
            for (name, value) in &v.attributes {
                let which = name.as_str();
                if !matches!(
                    which,
                    "start" | "fixed" | "nominal" | "min" | "max" | "stateSelect"
                ) {
                    continue;
                }
                let t = match self
                    .expr(value)
                    .and_then(|t| broadcast(t, dims, value.span))
                {
                    Ok(t) => t,
                    Err(e) => {
                        self.errors.push(e);
                        continue;
                    }
                };
                for k in 0..n {
                    let e = t.data[k];
                    let c = self.const_value(e);
                    let s = &mut self.dae.scalars[first.index() + k];
                    match which {
                        "start" => s.start = Some(e),
                        "nominal" => s.nominal = Some(e),
                        "min" => s.min = Some(e),
                        "max" => s.max = Some(e),
                        "fixed" => s.fixed = c.map(|x| x != 0.0),
                        _ => {
                            s.state_select = match c.map(|x| x as i64) {
                                Some(1) => StateSelect::Never,
                                Some(2) => StateSelect::Avoid,
                                Some(4) => StateSelect::Prefer,
                                Some(5) => StateSelect::Always,
                                _ => StateSelect::Default,
                            }
                        }
                    }
                }
            }
        }
    }
}
