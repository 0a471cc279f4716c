//! Equations and statements flattened: references made absolute, `for` equations
//! unrolled, structural `if`s decided, model algorithms' parameter loops unrolled.

use super::{Connect, Instantiator};
use crate::error::FlatError;
use crate::eval::{self, Value};
use crate::modif::Scope;
use unimo_syntax::ast::*;

impl Instantiator<'_, '_> {
    /// Whether `r`, an argument of a `connect` in the instance `scope`, is an outside
    /// connector (spec 9.1.2): a connector of the instance itself, or an element of one
    /// (`c.p` where the instance declares the connector `c`); `a.p` of a component `a`
    /// that is not a connector is inside.
    fn outside_connector(&self, r: &ComponentRef, scope: &Scope) -> bool {
        let Some(first) = r.parts.first() else {
            return false;
        };
        // In the simulated model itself, `p.a` of its own connector `p` stays an inside
        // connector (as before this rule): its flows are then set by the connection
        // and not also zeroed as an unconnected inside connector's.
        if r.parts.len() == 1 || scope.prefix.is_empty() {
            return r.parts.len() == 1;
        }
        let mut path = scope.prefix.to_vec();
        path.push(RefPart {
            name: first.name.clone(),
            subscripts: Vec::new(),
        });
        self.connector_keys
            .contains(&super::instance_key_no_subs(&path))
    }

    pub(super) fn equation(
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
                    a_outside: self.outside_connector(a, scope),
                    b_outside: self.outside_connector(b, scope),
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
            self.report(FlatError::ForWithoutRange {
                span: first.name.span,
            });
            return;
        };
        let flat = self.expr(range, scope, iters, &mut Vec::new());
        let values = match eval::eval(&flat, self, iters) {
            Ok(Value::Array(v)) => v,
            Ok(_) => {
                self.report(FlatError::ForRangeNotArray { span: range.span });
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
    pub(super) fn model_statements(
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

    pub(super) fn statement(
        &mut self,
        st: &Statement,
        scope: &Scope,
        locals: &mut Vec<String>,
    ) -> Statement {
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
