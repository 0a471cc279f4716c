//! Algorithms, symbolically executed: user-function bodies are inlined this way, and
//! model algorithm sections become one equation per assigned variable. Assignments
//! update a symbolic value; `if` with a non-constant condition runs both branches and
//! merges with `if`-expressions; `for` is unrolled; `while` must fold to a constant.

use crate::dae::{Assertion, WhenAction, WhenBranch, WhenClause};
use crate::error::{DaeError, DaeResult};
use crate::expr::{ExprId, ScalarId};
use crate::lower::{broadcast, unsupported, Local, Lowerer, MAX_INLINE_DEPTH_PUB};
use crate::tensor::Tensor;
use rustc_hash::FxHashMap as HashMap;
use unimo_flat::functions::FlatFunction;
use unimo_source::Span;
use unimo_syntax::ast::*;

/// Iterations of one `while` loop before it is given up.
const MAX_WHILE_ITERATIONS: usize = 1_000_000;

/// Copies of a `while` loop whose condition depends on variables (see
/// `unrolled_while`).
const UNROLLED_WHILE: usize = 64;

pub(crate) enum Flow {
    Next,
    Break,
    Return,
}

type Snapshot = (Vec<Local>, Option<HashMap<ScalarId, ExprId>>);

/// A `return` or `break` taken under a condition that depends on variables: when
/// `cond` holds, execution left with `state`; the statements after it run on the
/// other path. At the end of the function (`return`) or of the loop (`break`) the
/// exits are merged into the final state, earlier exits taking precedence.
pub(crate) struct Exit {
    is_return: bool,
    cond: ExprId,
    state: Snapshot,
}

impl Lowerer<'_> {
    fn snapshot(&self) -> Snapshot {
        (self.locals.clone(), self.assigned.clone())
    }

    fn restore(&mut self, s: Snapshot) {
        self.locals = s.0;
        self.assigned = s.1;
    }

    /// Merges the states after the two branches of `if c`.
    fn merge(&mut self, c: ExprId, then: Snapshot, other: Snapshot) {
        let (tl, ta) = then;
        let (ol, oa) = other;
        let mut locals = Vec::with_capacity(tl.len());
        for (t, o) in tl.into_iter().zip(ol) {
            let value = match (t.value, o.value) {
                (Some(a), Some(b)) if a.dims == b.dims => {
                    let data = a
                        .data
                        .iter()
                        .zip(&b.data)
                        .map(|(&x, &y)| self.dae.arena.if_(c, x, y))
                        .collect();
                    Some(Tensor { dims: a.dims, data })
                }
                (Some(a), _) => Some(a),
                (None, b) => b,
            };
            locals.push(Local {
                name: t.name,
                value,
                record: t.record,
                text: t.text,
            });
        }
        self.locals = locals;
        self.assigned = match (ta, oa) {
            (Some(ta), Some(oa)) => {
                let mut keys: Vec<ScalarId> = ta.keys().chain(oa.keys()).copied().collect();
                keys.sort();
                keys.dedup();
                let mut m = HashMap::default();
                for s in keys {
                    let dflt = self.unassigned_value(s);
                    let x = ta.get(&s).copied().unwrap_or(dflt);
                    let y = oa.get(&s).copied().unwrap_or(dflt);
                    m.insert(s, self.dae.arena.if_(c, x, y));
                }
                Some(m)
            }
            (a, _) => a,
        };
    }

    /// A model variable's value in an algorithm before it is assigned: `pre(v)` for
    /// discrete variables, `v` otherwise.
    fn unassigned_value(&mut self, s: ScalarId) -> ExprId {
        if self.dae.scalars[s.index()].kind == crate::dae::ScalarKind::Discrete {
            self.dae.arena.pre(s)
        } else {
            self.dae.arena.var(s)
        }
    }

    pub(crate) fn exec_block(&mut self, body: &[Statement]) -> DaeResult<Flow> {
        for st in body {
            match self.exec(st)? {
                Flow::Next => {}
                f => return Ok(f),
            }
        }
        Ok(Flow::Next)
    }

    fn exec(&mut self, st: &Statement) -> DaeResult<Flow> {
        match &st.kind {
            StatementKind::Assign { target, value } => {
                let v = self.expr(value)?;
                self.assign(target, v, st.span)?;
                Ok(Flow::Next)
            }
            StatementKind::MultiAssign { targets, value } => {
                let outs = self.call_outputs(value)?;
                for (t, v) in targets.iter().zip(outs) {
                    if let Some(t) = t {
                        let ExprKind::Ref(r) = &t.kind else {
                            return Err(unsupported("this assignment target", t.span));
                        };
                        self.assign(r, v, t.span)?;
                    }
                }
                Ok(Flow::Next)
            }
            StatementKind::Call(e) => {
                self.call_statement(e)?;
                Ok(Flow::Next)
            }
            StatementKind::If {
                branches,
                otherwise,
            } => self.exec_if(branches, otherwise, st.span),
            StatementKind::For { indices, body } => self.exec_for(indices, body),
            StatementKind::While { condition, body } => {
                let first_exit = self.exits.len();
                let flow = self.exec_while(condition, body, st.span);
                self.merge_exits(first_exit, false);
                flow
            }
            StatementKind::When { branches } => {
                self.when_statement(branches, st.span)?;
                Ok(Flow::Next)
            }
            StatementKind::Return => Ok(Flow::Return),
            StatementKind::Break => Ok(Flow::Break),
        }
    }

    fn exec_while(&mut self, condition: &Expr, body: &[Statement], span: Span) -> DaeResult<Flow> {
        {
            {
                for _ in 0..MAX_WHILE_ITERATIONS {
                    let c = self.scalar(condition)?;
                    match self.const_value(c) {
                        Some(0.0) => return Ok(Flow::Next),
                        Some(_) => {}
                        None => return self.unrolled_while(condition, body),
                    }
                    match self.exec_block(body)? {
                        Flow::Next => {}
                        Flow::Break => return Ok(Flow::Next),
                        Flow::Return => return Ok(Flow::Return),
                    }
                }
                Err(DaeError::EndlessLoop { span })
            }
        }
    }

    /// A `while` loop whose condition depends on variables (a table search
    /// `while next < nrow and t >= table[next, 1] loop next := next + 1; end while;`):
    /// unrolled [`UNROLLED_WHILE`] times as `if not condition then break; body`, the
    /// breaks merged as conditional exits. Past the last copy the condition must be
    /// false: a run-time assertion stops a simulation that would need more iterations
    /// instead of going on with a wrong value.
    fn unrolled_while(&mut self, condition: &Expr, body: &[Statement]) -> DaeResult<Flow> {
        let sp = condition.span;
        let stmt = |kind| Statement {
            kind,
            comment: Comment::default(),
            span: sp,
        };
        let not_condition = Expr {
            kind: ExprKind::Unary {
                op: UnaryOp::Not,
                operand: Box::new(condition.clone()),
            },
            span: sp,
        };
        let mut guarded = vec![stmt(StatementKind::If {
            branches: vec![(not_condition, vec![stmt(StatementKind::Break)])],
            otherwise: Vec::new(),
        })];
        guarded.extend(body.iter().cloned());
        let once = stmt(StatementKind::If {
            branches: vec![(
                Expr {
                    kind: ExprKind::Bool(true),
                    span: sp,
                },
                guarded,
            )],
            otherwise: Vec::new(),
        });
        for _ in 0..UNROLLED_WHILE {
            match self.exec_block(std::slice::from_ref(&once))? {
                Flow::Next => {}
                Flow::Break => return Ok(Flow::Next),
                Flow::Return => return Ok(Flow::Return),
            }
        }
        let c = self.scalar(condition)?;
        let ended = self.dae.arena.not(c);
        let message = format!(
            "a `while` loop needed more than {UNROLLED_WHILE} iterations (unimo unrolls a loop \
             whose condition depends on variables that many times)"
        );
        match &mut self.when_actions {
            Some(actions) => actions.push((
                WhenAction::Assert {
                    condition: ended,
                    message,
                },
                sp,
            )),
            None => self.dae.assertions.push(Assertion {
                condition: ended,
                message,
                warning: false,
                origin: sp,
            }),
        }
        Ok(Flow::Next)
    }

    fn exec_if(
        &mut self,
        branches: &[(Expr, Vec<Statement>)],
        otherwise: &[Statement],
        span: Span,
    ) -> DaeResult<Flow> {
        let Some(((cond, body), rest)) = branches.split_first() else {
            return self.exec_block(otherwise);
        };
        let c = self.scalar(cond)?;
        match self.const_value(c) {
            Some(x) if x != 0.0 => return self.exec_block(body),
            Some(_) => return self.exec_if(rest, otherwise, span),
            None => {}
        }
        let before = self.snapshot();
        let first_exit = self.exits.len();
        let first_checks = self.checks_len();
        let f1 = self.exec_block(body)?;
        self.guard_exits(first_exit, c);
        self.guard_checks(first_checks, c);
        let then = self.snapshot();
        self.restore(before);
        let not_c = self.dae.arena.not(c);
        let first_exit = self.exits.len();
        let first_checks = self.checks_len();
        let f2 = self.exec_if(rest, otherwise, span)?;
        self.guard_exits(first_exit, not_c);
        self.guard_checks(first_checks, not_c);
        let other = self.snapshot();
        match (f1, f2) {
            (Flow::Next, Flow::Next) => {
                self.merge(c, then, other);
                Ok(Flow::Next)
            }
            (Flow::Return, Flow::Return) => {
                self.merge(c, then, other);
                Ok(Flow::Return)
            }
            (Flow::Break, Flow::Break) => {
                self.merge(c, then, other);
                Ok(Flow::Break)
            }
            (Flow::Next, f) => {
                self.exits.push(Exit {
                    is_return: matches!(f, Flow::Return),
                    cond: not_c,
                    state: other,
                });
                self.restore(then);
                Ok(Flow::Next)
            }
            (f, Flow::Next) => {
                self.exits.push(Exit {
                    is_return: matches!(f, Flow::Return),
                    cond: c,
                    state: then,
                });
                self.restore(other);
                Ok(Flow::Next)
            }
            _ => Err(unsupported(
                "`return` in one branch and `break` in the other of an `if` whose condition depends on variables",
                span,
            )),
        }
    }

    /// How many `when` actions and assertions have been collected so far.
    fn checks_len(&self) -> (usize, usize) {
        let actions = self.when_actions.as_ref().map_or(0, Vec::len);
        (actions, self.dae.assertions.len())
    }

    /// The assertions collected since `first` (of [`Self::checks_len`]) are inside a
    /// branch entered when `c` holds: each checks `not c or condition`, so that an
    /// `assert` in a branch not taken holds.
    fn guard_checks(&mut self, first: (usize, usize), c: ExprId) {
        let not_c = self.dae.arena.not(c);
        if let Some(actions) = self.when_actions.as_mut() {
            for (action, _) in actions.iter_mut().skip(first.0) {
                if let WhenAction::Assert { condition, .. } = action {
                    *condition = self.dae.arena.or(not_c, *condition);
                }
            }
        }
        for a in self.dae.assertions.iter_mut().skip(first.1) {
            a.condition = self.dae.arena.or(not_c, a.condition);
        }
    }

    /// The exits recorded since `first` were taken inside a branch entered when `c`
    /// holds.
    fn guard_exits(&mut self, first: usize, c: ExprId) {
        for k in first..self.exits.len() {
            let cond = self.exits[k].cond;
            self.exits[k].cond = self.dae.arena.and(c, cond);
        }
    }

    /// Merges the exits since `first` of one kind (`returns`: the function's, else a
    /// loop's `break`s) into the current state, earlier ones taking precedence.
    pub(crate) fn merge_exits(&mut self, first: usize, returns: bool) {
        let tail: Vec<Exit> = self.exits.drain(first..).collect();
        let (mine, others): (Vec<Exit>, Vec<Exit>) =
            tail.into_iter().partition(|e| e.is_return == returns);
        self.exits.extend(others);
        for e in mine.into_iter().rev() {
            let current = self.snapshot();
            self.merge(e.cond, e.state, current);
        }
    }

    fn exec_for(&mut self, indices: &[ForIndex], body: &[Statement]) -> DaeResult<Flow> {
        let first_exit = self.exits.len();
        let flow = self.exec_for_indices(indices, body)?;
        self.merge_exits(first_exit, false);
        Ok(flow)
    }

    fn exec_for_indices(&mut self, indices: &[ForIndex], body: &[Statement]) -> DaeResult<Flow> {
        let Some((first, rest)) = indices.split_first() else {
            return self.exec_block(body);
        };
        let values = self.iterator_values(first)?;
        for v in values {
            match self.with_iterator(first, v, |me| me.exec_for_indices(rest, body))? {
                Flow::Next => {}
                Flow::Break => break,
                Flow::Return => return Ok(Flow::Return),
            }
        }
        Ok(Flow::Next)
    }

    /// `target := value`, into a local or a model variable.
    fn assign(&mut self, target: &ComponentRef, value: Tensor, span: Span) -> DaeResult<()> {
        let subs: Vec<Subscript> = target
            .parts
            .last()
            .map(|p| p.subscripts.clone())
            .unwrap_or_default();
        let local_pos = (!target.global && target.parts.len() == 1)
            .then(|| {
                self.locals
                    .iter()
                    .rposition(|l| l.name == target.parts[0].name.text.as_str())
            })
            .flatten();
        if let Some(k) = local_pos {
            let current = self.locals[k].value.clone();
            let new = if subs.is_empty() {
                value
            } else {
                let Some(mut cur) = current else {
                    return Err(DaeError::AssignedBeforeSized {
                        name: target.parts[0].name.text.to_string(),
                        span,
                    });
                };
                let positions = self.positions(&cur.dims, &subs)?;
                let v = broadcast(value, &[positions.len()], span)?;
                for (p, e) in positions.into_iter().zip(v.data) {
                    cur.data[p] = e;
                }
                cur
            };
            self.locals[k].value = Some(new);
            return Ok(());
        }
        // A field of a function's record variable (`c.re := ...`).
        if !target.global && target.parts.len() > 1 {
            let head = target.parts[0].name.text.as_str();
            if let Some(k) = self.locals.iter().rposition(|l| l.name == head) {
                if self.locals[k].record.is_some() {
                    return self.assign_record_field(k, &target.parts[1..], value, span);
                }
            }
        }
        // A model variable (algorithm section).
        let key = unimo_flat::eval::var_key(target);
        let Some((first, dims)) = self.vars.get(&key).cloned() else {
            return Err(DaeError::NotAssignable {
                name: key.to_string(),
                span,
            });
        };
        if self.assigned.is_none() {
            return Err(DaeError::FunctionAssignsModel {
                name: key.to_string(),
                span,
            });
        }
        if let Some(k) = self.dynamic_index(&dims, &subs)? {
            return self.assign_dynamic(first, dims[0], k, value, span);
        }
        let positions = if subs.is_empty() {
            (0..dims.iter().product()).collect()
        } else {
            self.positions(&dims, &subs)?
        };
        let v = broadcast(value, &[positions.len()], span)?;
        let assigned = self.assigned.as_mut().expect("checked above");
        for (p, e) in positions.into_iter().zip(v.data) {
            assigned.insert(ScalarId(first.0 + p as u32), e);
        }
        Ok(())
    }

    /// The index of `v[i] := ..` of a vector `v` when `i` is a scalar not known at
    /// compile time (`buf[iTick] := u`); `None` otherwise.
    fn dynamic_index(&mut self, dims: &[usize], subs: &[Subscript]) -> DaeResult<Option<ExprId>> {
        let [Subscript::Expr(e)] = subs else {
            return Ok(None);
        };
        if dims.len() != 1 || matches!(e.kind, ExprKind::Integer(_) | ExprKind::Range { .. }) {
            return Ok(None);
        }
        self.end_stack.push(dims[0]);
        let t = self.expr(e);
        self.end_stack.pop();
        let t = t?;
        if !t.is_scalar() || self.const_value(t.data[0]).is_some() {
            return Ok(None);
        }
        Ok(Some(t.data[0]))
    }

    /// `v[i] := x` with `i` known only at run time: every element `k` of the vector
    /// becomes `if i == k then x else v[k]` (an index outside 1..n assigns nothing).
    fn assign_dynamic(
        &mut self,
        first: ScalarId,
        n: usize,
        index: ExprId,
        value: Tensor,
        span: Span,
    ) -> DaeResult<()> {
        let x = broadcast(value, &[], span)?.data[0];
        for k in 0..n {
            let s = ScalarId(first.0 + k as u32);
            let old = self.current_value(s);
            let ar = self.a();
            let kk = ar.constant((k + 1) as f64);
            let hit = ar.rel(crate::expr::RelOp::Eq, index, kk);
            let hit = ar.no_event(hit);
            let new = ar.if_(hit, x, old);
            self.assigned
                .as_mut()
                .expect("checked by the caller")
                .insert(s, new);
        }
        Ok(())
    }

    /// Row-major positions selected by constant subscripts of an array of size `dims`.
    pub(crate) fn positions(
        &mut self,
        dims: &[usize],
        subs: &[Subscript],
    ) -> DaeResult<Vec<usize>> {
        let mut pos = vec![0usize];
        for (d, &n) in dims.iter().enumerate() {
            let picks: Vec<usize> = match subs.get(d) {
                None | Some(Subscript::Colon(_)) => (0..n).collect(),
                Some(Subscript::Expr(e)) => {
                    self.end_stack.push(n);
                    let t = self.expr(e);
                    self.end_stack.pop();
                    let t = t?;
                    let mut out = Vec::new();
                    for &x in &t.data {
                        let k = self
                            .const_value(x)
                            .ok_or(DaeError::AssignedIndexNotConstant { span: e.span })?
                            as i64;
                        if k < 1 || k as usize > n {
                            return Err(DaeError::IndexOutOfBounds {
                                index: k,
                                size: n,
                                span: e.span,
                            });
                        }
                        out.push(k as usize - 1);
                    }
                    out
                }
            };
            pos = pos
                .into_iter()
                .flat_map(|p| picks.iter().map(move |&k| p * n + k))
                .collect();
        }
        Ok(pos)
    }

    /// The outputs of a user-function call expression.
    pub(crate) fn call_outputs(&mut self, e: &Expr) -> DaeResult<Vec<Tensor>> {
        if let ExprKind::Call { func, args } = &e.kind {
            if func.global {
                let name = func.to_dotted();
                if let Some(f) = self.functions.get(name.trim_start_matches('.')).copied() {
                    return self.inline_call(f, args, e.span);
                }
            }
        }
        Ok(vec![self.expr(e)?])
    }

    /// `assert`, `terminate`, `reinit` as statements; other calls are dropped (with
    /// `W3001` when their effects are lost).
    fn call_statement(&mut self, e: &Expr) -> DaeResult<()> {
        let ExprKind::Call { func, args } = &e.kind else {
            return Err(unsupported("this statement", e.span));
        };
        let action = self.action_call(&func.to_dotted(), args, e.span)?;
        if action.is_none() && self.calls_effect(func) {
            // Its effect is recorded while inlining; a function without outputs then
            // has nothing to return, which is no error here.
            match self.call_outputs(e) {
                Err(err) if matches!(err.innermost(), DaeError::NoOutput { .. }) => {}
                r => {
                    r?;
                }
            }
        } else if action.is_none() {
            self.warn_unexecuted(func, e.span);
        }
        if let Some(a) = action {
            match &mut self.when_actions {
                Some(actions) => actions.push((a, e.span)),
                None => match a {
                    WhenAction::Assert { condition, message } => {
                        let warning = is_warning(args);
                        self.dae.assertions.push(Assertion {
                            condition,
                            message,
                            warning,
                            origin: e.span,
                        })
                    }
                    WhenAction::Reinit { .. } => {
                        return Err(DaeError::ReinitOutsideWhen { span: e.span })
                    }
                    _ => {
                        return Err(unsupported("`terminate` outside `when`", e.span));
                    }
                },
            }
        }
        Ok(())
    }

    /// Whether `func` is an external function unimo provides whose call statement has
    /// an effect (other calls whose outputs are not used are dropped).
    fn calls_effect(&self, func: &Name) -> bool {
        let name = func.to_dotted();
        self.functions
            .get(name.trim_start_matches('.'))
            .and_then(|f| f.external_call.as_ref())
            .is_some_and(|ext| crate::external::has_effect(&ext.function))
    }

    /// `reinit`, `assert` or `terminate` as an action; `None` for other calls.
    pub(crate) fn action_call(
        &mut self,
        name: &str,
        args: &CallArgs,
        span: Span,
    ) -> DaeResult<Option<WhenAction>> {
        Ok(Some(match name {
            "reinit" => {
                let (Some(target), Some(value)) = (args.positional.first(), args.positional.get(1))
                else {
                    return Err(DaeError::ReinitArguments { span });
                };
                let t = self.expr(target)?;
                let v = self.expr(value)?;
                let v = broadcast(v, &t.dims, span)?;
                if t.data.len() != 1 {
                    // reinit of an array: one action per element is made by the caller.
                    return Err(unsupported(
                        "`reinit` of a whole array (reinit each element)",
                        span,
                    ));
                }
                let crate::expr::Node::Var(s) = self.dae.arena.node(t.data[0]) else {
                    return Err(DaeError::ReinitNeedsVariable { span: target.span });
                };
                WhenAction::Reinit {
                    state: s,
                    value: v.data[0],
                }
            }
            "assert" => {
                let Some(c) = args.positional.first() else {
                    return Err(DaeError::AssertWithoutCondition { span });
                };
                let condition = self.scalar(c)?;
                let message = match args.positional.get(1).map(|m| &m.kind) {
                    Some(ExprKind::String(s)) => s.clone(),
                    _ => "assertion failed".into(),
                };
                WhenAction::Assert { condition, message }
            }
            "terminate" => {
                let message = match args.positional.first().map(|m| &m.kind) {
                    Some(ExprKind::String(s)) => s.clone(),
                    _ => "terminate() was called".into(),
                };
                WhenAction::Terminate { message }
            }
            _ => return Ok(None),
        }))
    }

    fn when_statement(&mut self, branches: &[(Expr, Vec<Statement>)], span: Span) -> DaeResult<()> {
        let mut clause = WhenClause {
            branches: Vec::new(),
            origin: span,
        };
        for (cond, body) in branches {
            let conditions = self.expr(cond)?.data;
            let saved_assigned = self.assigned.replace(HashMap::default());
            let saved_actions = self.when_actions.replace(Vec::new());
            let r = self.exec_block(body);
            let assigned =
                std::mem::replace(&mut self.assigned, saved_assigned).unwrap_or_default();
            let mut actions =
                std::mem::replace(&mut self.when_actions, saved_actions).unwrap_or_default();
            r?;
            let mut assigned: Vec<_> = assigned.into_iter().collect();
            assigned.sort_by_key(|(s, _)| *s);
            actions.splice(
                0..0,
                assigned
                    .into_iter()
                    .map(|(target, value)| (WhenAction::Assign { target, value }, span)),
            );
            clause.branches.push(WhenBranch {
                conditions,
                actions,
            });
        }
        self.dae.whens.push(clause);
        Ok(())
    }

    /// Inlines a call of `f`: binds the arguments, executes the body symbolically and
    /// returns the outputs.
    pub(crate) fn inline_call(
        &mut self,
        f: &FlatFunction,
        args: &CallArgs,
        span: Span,
    ) -> DaeResult<Vec<Tensor>> {
        if self.inline_depth >= MAX_INLINE_DEPTH_PUB {
            return Err(DaeError::InliningTooDeep {
                function: f.name.to_string(),
                span,
            });
        }
        if f.external && f.external_call.is_none() {
            return Err(unsupported(format!("external function `{}`", f.name), span));
        }
        let mut given: Vec<Option<Tensor>> = vec![None; f.inputs.len()];
        let mut texts: Vec<Option<String>> = vec![None; f.inputs.len()];
        // String inputs have no numeric value: their text is kept where it is known
        // (a literal, `getInstanceName()`, another String input) for the functions
        // unimo provides that read it (a hash); a table's file name is not read.
        let skip = |k: usize| f.inputs[k].base == "String";
        for (k, a) in args.positional.iter().enumerate() {
            if k >= given.len() {
                return Err(DaeError::TooManyArguments {
                    function: f.name.to_string(),
                    span: a.span,
                });
            }
            if skip(k) {
                given[k] = Some(Tensor::default());
                texts[k] = self.text_value(a);
                continue;
            }
            given[k] = Some(self.expr(a)?);
        }
        for a in &args.named {
            let Some(k) = f.inputs.iter().position(|i| i.name == a.name.text.as_str()) else {
                return Err(DaeError::NoSuchInput {
                    function: f.name.to_string(),
                    input: a.name.text.to_string(),
                    span: a.name.span,
                });
            };
            given[k] = Some(if skip(k) {
                texts[k] = self.text_value(&a.value);
                Tensor::default()
            } else {
                self.expr(&a.value)?
            });
        }
        let saved_locals = std::mem::take(&mut self.locals);
        let saved_assigned = self.assigned.take();
        let saved_actions = self.when_actions.take();
        let saved_exits = std::mem::take(&mut self.exits);
        self.inline_depth += 1;
        let r = self.run_function(f, given, texts, span);
        self.inline_depth -= 1;
        self.locals = saved_locals;
        self.assigned = saved_assigned;
        self.when_actions = saved_actions;
        self.exits = saved_exits;
        r.map_err(|e| e.while_inlining(&f.name))
    }

    /// The text of a String expression where it is known at compile time: a literal,
    /// a String input bound to one, or a concatenation of such.
    pub(crate) fn text_value(&self, e: &Expr) -> Option<String> {
        match &e.kind {
            ExprKind::String(s) => Some(s.clone()),
            ExprKind::Ref(r) if r.parts.len() == 1 && r.parts[0].subscripts.is_empty() => {
                let name = r.parts[0].name.text.as_str();
                self.locals
                    .iter()
                    .rev()
                    .find(|l| l.name == name)?
                    .text
                    .clone()
            }
            ExprKind::Binary {
                op: BinaryOp::Add,
                lhs,
                rhs,
            } => Some(self.text_value(lhs)? + &self.text_value(rhs)?),
            _ => None,
        }
    }

    /// The sizes of a function's output or local, its size expressions evaluated with
    /// the inputs bound (`output Real y[n]` where `n` is an input known here).
    fn function_var_dims(&mut self, v: &unimo_flat::functions::FuncVar) -> Option<Vec<usize>> {
        let mut out = Vec::with_capacity(v.dims.len());
        for (k, d) in v.dims.iter().enumerate() {
            let n = match d {
                Some(n) => *n,
                None => {
                    let e = v.dim_exprs.get(k)?.as_ref()?;
                    let t = self.expr(e).ok()?;
                    let x = self.const_value(*t.data.first()?)?;
                    if x < 0.0 || x != x.trunc() {
                        return None;
                    }
                    x as usize
                }
            };
            out.push(n);
        }
        Some(out)
    }

    fn run_function(
        &mut self,
        f: &FlatFunction,
        given: Vec<Option<Tensor>>,
        texts: Vec<Option<String>>,
        span: Span,
    ) -> DaeResult<Vec<Tensor>> {
        for ((input, value), text) in f.inputs.iter().zip(given).zip(texts) {
            let string = input.base == "String";
            let text = match (&input.default, string, text) {
                (_, _, Some(t)) => Some(t),
                (Some(d), true, None) => self.text_value(d),
                _ => None,
            };
            let value = match value {
                Some(v) => v,
                None if string => Tensor::default(),
                None => match &input.default {
                    Some(d) => self.expr(d)?,
                    None => {
                        return Err(DaeError::InputNotGiven {
                            input: input.name.to_string(),
                            function: f.name.to_string(),
                            span,
                        })
                    }
                },
            };
            self.locals.push(Local {
                name: input.name.clone(),
                value: Some(value),
                record: input.record.clone(),
                text,
            });
        }
        for v in f.outputs.iter().chain(&f.locals) {
            let value = match &v.default {
                Some(d) => Some(self.expr(d)?),
                None if v.record.is_some() => {
                    let n = self.record_local_size(v, span)?;
                    let nan = self.dae.arena.constant(f64::NAN);
                    Some(Tensor {
                        data: vec![nan; n],
                        dims: vec![n],
                    })
                }
                None if !v.dims.is_empty() && self.function_var_dims(v).is_some() => {
                    let dims = self.function_var_dims(v).unwrap_or_default();
                    let nan = self.dae.arena.constant(f64::NAN);
                    Some(Tensor {
                        data: vec![nan; dims.iter().product()],
                        dims,
                    })
                    .filter(|t| !t.dims.is_empty())
                }
                None => None,
            };
            self.locals.push(Local {
                name: v.name.clone(),
                value,
                record: v.record.clone(),
                text: None,
            });
        }
        match &f.external_call {
            Some(ext) if f.external => self.external_body(f, ext, span)?,
            _ => {
                let first_exit = self.exits.len();
                self.exec_block(&f.algorithm)?;
                self.merge_exits(first_exit, true);
            }
        }
        let mut outs = Vec::new();
        for o in &f.outputs {
            let v = self
                .locals
                .iter()
                .rev()
                .find(|l| l.name == o.name)
                .and_then(|l| l.value.clone())
                .ok_or_else(|| DaeError::OutputNeverAssigned {
                    output: o.name.to_string(),
                    function: f.name.to_string(),
                    span,
                })?;
            outs.push(v);
        }
        if outs.is_empty() {
            return Err(DaeError::NoOutput {
                function: f.name.to_string(),
                span,
            });
        }
        Ok(outs)
    }

    /// A model algorithm section: each assigned variable gets the equation
    /// `v = <its final symbolic value>`; `when` statements become `when` clauses.
    pub(crate) fn algorithm(&mut self, body: &[Statement], span: Span) -> DaeResult<()> {
        self.assigned = Some(HashMap::default());
        let r = self.exec_block(body);
        let assigned = self.assigned.take().unwrap_or_default();
        r?;
        let mut assigned: Vec<_> = assigned.into_iter().collect();
        assigned.sort_by_key(|(s, _)| *s);
        for (s, value) in assigned {
            let lhs = self.dae.arena.var(s);
            self.dae.equations.push(crate::dae::Equation {
                lhs,
                rhs: value,
                origin: span,
                derivative_of: None,
            });
        }
        Ok(())
    }
}

fn is_warning(args: &CallArgs) -> bool {
    args.positional
        .get(2)
        .or_else(|| {
            args.named
                .iter()
                .find(|a| a.name.text == "level")
                .map(|a| &a.value)
        })
        .is_some_and(|e| match &e.kind {
            ExprKind::Ref(r) => r.to_dotted().ends_with("warning"),
            _ => false,
        })
}
