//! Lowering of equations: simple equations scalarized, `if`-equations with
//! non-parameter conditions turned into switched residuals (one per row, every branch
//! with the same count), `when` equations into clauses with actions, and the entry
//! point [`lower`].

use crate::dae::*;
use crate::error::{DaeError, DaeResult};
use crate::expr::{ExprId, Node, ScalarId};
use crate::fold::FoldOptions;
use crate::lower::{broadcast, unsupported, Lowerer};
use crate::tensor::Tensor;
use unimo_flat::FlatModel;
use unimo_source::{Diagnostic, Span};
use unimo_syntax::ast::{self, EquationKind, Expr, ExprKind};

/// Lowers a flat model to the hybrid DAE. Errors are coded `E30xx` diagnostics; when
/// there are any, the DAE is incomplete.
pub fn lower(model: &FlatModel) -> (Dae, Vec<Diagnostic>) {
    lower_with(model, &FoldOptions::default())
}

/// [`lower`] with a choice of the parameters kept tunable (the others are folded).
pub fn lower_with(model: &FlatModel, fold: &FoldOptions) -> (Dae, Vec<Diagnostic>) {
    let mut l = Lowerer::new(model);
    l.declare_vars();
    l.var_attributes();
    l.evaluate_parameters(fold);
    for eq in &model.equations {
        match l.equation_rows(eq) {
            Ok(rows) => l.dae.equations.extend(rows),
            Err(e) => l.errors.push(e),
        }
    }
    for eq in &model.initial_equations {
        match l.equation_rows(eq) {
            Ok(rows) => l.dae.initial_equations.extend(rows),
            Err(e) => l.errors.push(e),
        }
    }
    for alg in &model.algorithms {
        let span = alg.first().map(|s| s.span).unwrap_or_default();
        if let Err(e) = l.algorithm(alg, span) {
            l.errors.push(e);
        }
    }
    for alg in &model.initial_algorithms {
        let span = alg.first().map(|s| s.span).unwrap_or_default();
        let before = l.dae.equations.len();
        if let Err(e) = l.algorithm(alg, span) {
            l.errors.push(e);
        }
        let moved: Vec<_> = l.dae.equations.drain(before..).collect();
        l.dae.initial_equations.extend(moved);
    }
    l.expand_impure_random();
    l.experiment();
    l.finish_kinds();
    let mut diags: Vec<Diagnostic> = l.errors.iter().map(|e| e.to_diagnostic()).collect();
    diags.append(&mut l.dae.warnings);
    (l.dae, diags)
}

impl Lowerer<'_> {
    /// The scalar rows of one equation (when-equations go to `dae.whens`; asserts to
    /// `dae.assertions`).
    fn equation_rows(&mut self, eq: &ast::Equation) -> DaeResult<Vec<Equation>> {
        let span = eq.span;
        match &eq.kind {
            EquationKind::Simple { lhs, rhs } => self.simple(lhs, rhs, span),
            EquationKind::Call(e) => {
                let ExprKind::Call { func, args } = &e.kind else {
                    return Err(unsupported("this equation", span));
                };
                let name = func.to_dotted();
                if name == "invariant" {
                    return self.invariant(args, span);
                }
                match self.action_call(&name, args, span)? {
                    Some(WhenAction::Assert { condition, message }) => {
                        let warning = args.positional.get(2).is_some_and(|e| {
                            matches!(&e.kind, ExprKind::Ref(r) if r.to_dotted().ends_with("warning"))
                        });
                        self.dae.assertions.push(Assertion {
                            condition,
                            message,
                            warning,
                            origin: span,
                        });
                        Ok(Vec::new())
                    }
                    Some(WhenAction::Reinit { .. }) => Err(DaeError::ReinitOutsideWhen { span }),
                    Some(_) => Err(unsupported("`terminate` outside `when`", span)),
                    None => {
                        self.warn_unexecuted(func, span);
                        Ok(Vec::new())
                    }
                }
            }
            EquationKind::Connect { .. } => Err(DaeError::ConnectAfterFlattening { span }),
            EquationKind::For { indices, body } => self.for_rows(indices, body),
            EquationKind::If {
                branches,
                otherwise,
            } => self.if_rows(branches, otherwise, span),
            EquationKind::When { branches } => {
                self.when_equation(branches, span)?;
                Ok(Vec::new())
            }
        }
    }

    fn for_rows(
        &mut self,
        indices: &[ast::ForIndex],
        body: &[ast::Equation],
    ) -> DaeResult<Vec<Equation>> {
        let Some((first, rest)) = indices.split_first() else {
            let mut out = Vec::new();
            for e in body {
                out.extend(self.equation_rows(e)?);
            }
            return Ok(out);
        };
        let mut out = Vec::new();
        for v in self.iterator_values(first)? {
            out.extend(self.with_iterator(first, v, |me| me.for_rows(rest, body))?);
        }
        Ok(out)
    }

    fn simple(&mut self, lhs: &Expr, rhs: &Expr, span: Span) -> DaeResult<Vec<Equation>> {
        if let ExprKind::Tuple(targets) = &lhs.kind {
            let outs = self.call_outputs(rhs)?;
            let mut rows = Vec::new();
            for (t, v) in targets.iter().zip(outs) {
                if let Some(t) = t {
                    let l = self.expr(t)?;
                    rows.extend(self.rows(l, v, span)?);
                }
            }
            return Ok(rows);
        }
        let l = self.expr(lhs)?;
        let r = self.expr(rhs)?;
        self.rows(l, r, span)
    }

    fn rows(&mut self, l: Tensor, r: Tensor, span: Span) -> DaeResult<Vec<Equation>> {
        let r = if l.dims == r.dims || r.data.len() != l.data.len() {
            r
        } else {
            broadcast(r, &l.dims.clone(), span)?
        };
        if l.data.len() != r.data.len() {
            return Err(DaeError::SizesDiffer {
                left: l.dims,
                right: r.dims,
                equation: true,
                span,
            });
        }
        Ok(l.data
            .into_iter()
            .zip(r.data)
            .map(|(lhs, rhs)| Equation {
                lhs,
                rhs,
                origin: span,
                derivative_of: None,
            })
            .collect())
    }

    /// `if c1 then A elseif c2 then B else C end if` with rows r_i: the i-th row is
    /// `0 = if c1 then A_i else if c2 then B_i else C_i`.
    fn if_rows(
        &mut self,
        branches: &[(Expr, Vec<ast::Equation>)],
        otherwise: &[ast::Equation],
        span: Span,
    ) -> DaeResult<Vec<Equation>> {
        let mut conds = Vec::new();
        let mut bodies = Vec::new();
        // The invariants of a branch hold where it is taken: the earlier conditions
        // false and its own true.
        let mut taken = self.dae.arena.one();
        for (c, body) in branches {
            let c = self.scalar(c)?;
            match self.const_value(c) {
                Some(x) if x != 0.0 && conds.is_empty() => return self.body_rows(body),
                Some(0.0) => continue,
                _ => {}
            }
            conds.push(c);
            let first = self.dae.invariants.len();
            bodies.push(self.body_rows(body)?);
            let here = self.dae.arena.and(taken, c);
            self.guard_invariants(first, here);
            let not_c = self.dae.arena.not(c);
            taken = self.dae.arena.and(taken, not_c);
        }
        let first = self.dae.invariants.len();
        let other = self.body_rows(otherwise)?;
        self.guard_invariants(first, taken);
        if conds.is_empty() {
            return Ok(other);
        }
        let n = other.len();
        for (k, b) in bodies.iter().enumerate() {
            if b.len() != n {
                return Err(DaeError::UnequalIfBranches {
                    count: b.len(),
                    branch: k + 1,
                    else_count: n,
                    span,
                });
            }
        }
        let mut rows = Vec::with_capacity(n);
        for i in 0..n {
            let mut acc = self.dae.arena.sub(other[i].lhs, other[i].rhs);
            for k in (0..conds.len()).rev() {
                let r = self.dae.arena.sub(bodies[k][i].lhs, bodies[k][i].rhs);
                acc = self.dae.arena.if_(conds[k], r, acc);
            }
            let zero = self.dae.arena.zero();
            rows.push(Equation {
                lhs: acc,
                rhs: zero,
                origin: span,
                derivative_of: None,
            });
        }
        Ok(rows)
    }

    /// `Unimo.invariant(g)`: one invariant per element of `g`, active everywhere until
    /// an enclosing if-equation guards it ([`Self::guard_invariants`]). No rows: `g = 0`
    /// is kept by the simulator's projection, not solved for.
    fn invariant(&mut self, args: &ast::CallArgs, span: Span) -> DaeResult<Vec<Equation>> {
        let (Some(g), 1, true) = (
            args.positional.first(),
            args.positional.len(),
            args.named.is_empty(),
        ) else {
            return Err(DaeError::InvariantArguments { span });
        };
        let active = self.dae.arena.one();
        for value in self.expr(g)?.data {
            self.dae.invariants.push(Invariant {
                value,
                active,
                origin: span,
            });
        }
        Ok(Vec::new())
    }

    /// The invariants collected since `first` stand in a branch taken when `c` holds.
    fn guard_invariants(&mut self, first: usize, c: ExprId) {
        for k in first..self.dae.invariants.len() {
            let active = self.dae.invariants[k].active;
            self.dae.invariants[k].active = self.dae.arena.and(c, active);
        }
    }

    fn body_rows(&mut self, body: &[ast::Equation]) -> DaeResult<Vec<Equation>> {
        let mut out = Vec::new();
        for e in body {
            if matches!(e.kind, EquationKind::When { .. }) {
                return Err(unsupported("`when` inside an if-equation", e.span));
            }
            out.extend(self.equation_rows(e)?);
        }
        Ok(out)
    }

    fn when_equation(
        &mut self,
        branches: &[(Expr, Vec<ast::Equation>)],
        span: Span,
    ) -> DaeResult<()> {
        let mut clause = WhenClause {
            branches: Vec::new(),
            origin: span,
        };
        for (cond, body) in branches {
            let conditions = self.expr(cond)?.data;
            let mut actions = Vec::new();
            for eq in body {
                self.when_body(eq, &mut actions)?;
            }
            clause.branches.push(WhenBranch {
                conditions,
                actions,
            });
        }
        self.dae.whens.push(clause);
        Ok(())
    }

    fn when_body(
        &mut self,
        eq: &ast::Equation,
        actions: &mut Vec<(WhenAction, Span)>,
    ) -> DaeResult<()> {
        let span = eq.span;
        match &eq.kind {
            EquationKind::Simple { lhs, rhs } => self.when_assignment(lhs, rhs, span, actions),
            EquationKind::Call(e) => self.when_call(e, span, actions),
            EquationKind::If {
                branches,
                otherwise,
            } => {
                // Each target gets `if c then value else <other branches>`; a target a
                // branch does not assign keeps its pre-value there.
                let mut conds = Vec::new();
                let mut branch_actions = Vec::new();
                for (c, body) in branches {
                    conds.push(self.scalar(c)?);
                    let mut acts = Vec::new();
                    for e in body {
                        self.when_body(e, &mut acts)?;
                    }
                    branch_actions.push(acts);
                }
                let mut other = Vec::new();
                for e in otherwise {
                    self.when_body(e, &mut other)?;
                }
                self.merge_when_if(&conds, branch_actions, other, actions);
                Ok(())
            }
            EquationKind::For { indices, body } => {
                let Some(first) = indices.first() else {
                    return Ok(());
                };
                if indices.len() > 1 {
                    return Err(unsupported(
                        "a `for` with several iterators in `when`",
                        span,
                    ));
                }
                for v in self.iterator_values(first)? {
                    self.with_iterator(first, v, |me| {
                        body.iter().try_for_each(|e| me.when_body(e, actions))
                    })?;
                }
                Ok(())
            }
            EquationKind::When { .. } => Err(DaeError::NestedWhen { span }),
            EquationKind::Connect { .. } => Err(unsupported("`connect` inside `when`", span)),
        }
    }

    /// A call in `when`: `reinit` (of an array too), `terminate`, `assert` and the other
    /// actions.
    fn when_call(
        &mut self,
        e: &Expr,
        span: Span,
        actions: &mut Vec<(WhenAction, Span)>,
    ) -> DaeResult<()> {
        let ExprKind::Call { func, args } = &e.kind else {
            return Err(unsupported("this equation in `when`", span));
        };
        let name = func.to_dotted();
        if name == "reinit" {
            if let Some(target) = args.positional.first() {
                let t = self.expr(target)?;
                if t.data.len() > 1 {
                    let v = self.expr(&args.positional[1])?;
                    let v = broadcast(v, &t.dims, span)?;
                    for (&x, &e) in t.data.iter().zip(&v.data) {
                        let Node::Var(s) = self.dae.arena.node(x) else {
                            return Err(DaeError::ReinitNeedsVariable { span: target.span });
                        };
                        actions.push((WhenAction::Reinit { state: s, value: e }, span));
                    }
                    return Ok(());
                }
            }
        }
        match self.action_call(&name, args, span)? {
            Some(a) => actions.push((a, span)),
            None => self.warn_unexecuted(func, span),
        }
        Ok(())
    }

    /// An equation `lhs = rhs` in `when` (`(a, b) = f(x)` too): one assignment per scalar
    /// of the left side, which must be variables.
    fn when_assignment(
        &mut self,
        lhs: &Expr,
        rhs: &Expr,
        span: Span,
        actions: &mut Vec<(WhenAction, Span)>,
    ) -> DaeResult<()> {
        let outs = match &lhs.kind {
            ExprKind::Tuple(_) => self.call_outputs(rhs)?,
            _ => vec![self.expr(rhs)?],
        };
        let targets: Vec<&Expr> = match &lhs.kind {
            ExprKind::Tuple(t) => t.iter().flatten().collect(),
            _ => vec![lhs],
        };
        for (t, v) in targets.into_iter().zip(outs) {
            let tt = self.expr(t)?;
            let v = broadcast(v, &tt.dims, span)?;
            for (&x, &e) in tt.data.iter().zip(&v.data) {
                let Node::Var(s) = self.dae.arena.node(x) else {
                    return Err(DaeError::WhenTargetNotVariable { span: t.span });
                };
                actions.push((
                    WhenAction::Assign {
                        target: s,
                        value: e,
                    },
                    span,
                ));
            }
        }
        Ok(())
    }

    fn merge_when_if(
        &mut self,
        conds: &[ExprId],
        branches: Vec<Vec<(WhenAction, Span)>>,
        other: Vec<(WhenAction, Span)>,
        out: &mut Vec<(WhenAction, Span)>,
    ) {
        #[derive(PartialEq, Clone, Copy)]
        enum Key {
            Assign(ScalarId),
            Reinit(ScalarId),
        }
        let key = |a: &WhenAction| match a {
            WhenAction::Assign { target, .. } => Some(Key::Assign(*target)),
            WhenAction::Reinit { state, .. } => Some(Key::Reinit(*state)),
            _ => None,
        };
        let value = |a: &WhenAction| match a {
            WhenAction::Assign { value, .. } | WhenAction::Reinit { value, .. } => Some(*value),
            _ => None,
        };
        let mut keys: Vec<(Key, Span)> = Vec::new();
        for (a, s) in branches.iter().flatten().chain(&other) {
            if let Some(k) = key(a) {
                if !keys.iter().any(|(x, _)| *x == k) {
                    keys.push((k, *s));
                }
            }
        }
        for (k, span) in keys {
            let default = match k {
                Key::Assign(s) => self.dae.arena.pre(s),
                Key::Reinit(s) => self.dae.arena.var(s),
            };
            let find = |acts: &[(WhenAction, Span)]| {
                acts.iter()
                    .find(|(a, _)| key(a) == Some(k))
                    .and_then(|(a, _)| value(a))
            };
            let mut acc = find(&other).unwrap_or(default);
            for (c, acts) in conds.iter().zip(&branches).rev() {
                let v = find(acts).unwrap_or(default);
                acc = self.dae.arena.if_(*c, v, acc);
            }
            out.push((
                match k {
                    Key::Assign(target) => WhenAction::Assign { target, value: acc },
                    Key::Reinit(state) => WhenAction::Reinit { state, value: acc },
                },
                span,
            ));
        }
        // Asserts and terminations inside if-branches of a when: kept unconditionally
        // is wrong, so they are guarded by their branch's condition.
        for (c, acts) in conds.iter().zip(branches) {
            for (a, s) in acts {
                if let WhenAction::Assert { condition, message } = a {
                    let nc = self.dae.arena.not(*c);
                    let cond = self.dae.arena.or(nc, condition);
                    out.push((
                        WhenAction::Assert {
                            condition: cond,
                            message,
                        },
                        s,
                    ));
                }
            }
        }
    }

    /// `annotation(experiment(StartTime = ..., StopTime = ..., Tolerance = ..., Interval = ...))`.
    pub(crate) fn experiment(&mut self) {
        let Some(m) = &self.model.experiment else {
            return;
        };
        for arg in &m.args {
            let ast::Argument::Modify {
                name,
                modification: Some(md),
                ..
            } = arg
            else {
                continue;
            };
            let Some(b) = &md.binding else {
                continue;
            };
            if name.to_dotted() == "__unimo_method" {
                self.experiment_method(b);
                continue;
            }
            let value = self.scalar(b).ok().and_then(|x| self.const_value(x));
            let e = &mut self.dae.experiment;
            match name.to_dotted().as_str() {
                "StartTime" => e.start_time = value,
                "StopTime" => e.stop_time = value,
                "Tolerance" => e.tolerance = value,
                "Interval" => e.interval = value,
                _ => {}
            }
        }
    }

    /// `__unimo_method = "name"`: a string literal naming one of [`METHOD_NAMES`].
    fn experiment_method(&mut self, b: &ast::Expr) {
        match &b.kind {
            ast::ExprKind::String(m) if METHOD_NAMES.contains(&m.as_str()) => {
                self.dae.experiment.method = Some(m.clone());
            }
            _ => self.errors.push(DaeError::UnknownMethod {
                given: unimo_syntax::print::expr(b),
                span: b.span,
            }),
        }
    }

    /// Real variables assigned in `when` are discrete; `reinit` needs a state.
    pub(crate) fn finish_kinds(&mut self) {
        let mut assigned = Vec::new();
        let mut reinits = Vec::new();
        for w in &self.dae.whens {
            for b in &w.branches {
                for (a, span) in &b.actions {
                    match a {
                        WhenAction::Assign { target, .. } => assigned.push(*target),
                        WhenAction::Reinit { state, .. } => reinits.push((*state, *span)),
                        _ => {}
                    }
                }
            }
        }
        for s in assigned {
            let sc = &mut self.dae.scalars[s.index()];
            if sc.kind == ScalarKind::Continuous {
                sc.kind = ScalarKind::Discrete;
            }
        }
        for (s, span) in reinits {
            let sc = &self.dae.scalars[s.index()];
            if sc.derivative.is_none() || sc.kind != ScalarKind::Continuous {
                self.errors.push(DaeError::ReinitOfNonState {
                    name: sc.name.to_string(),
                    span,
                });
            }
        }
    }
}
