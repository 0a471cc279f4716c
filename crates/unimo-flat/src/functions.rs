//! The user functions a flat model calls: their signatures and algorithm bodies with
//! names resolved (calls made global, package constants inlined), for the back end.

use crate::eval::{self, Value};
use crate::instantiate::Instantiator;
use crate::lookup::Found;
use crate::modif::Scope;
use crate::tree::ClassId;
use unimo_source::Span;
use unimo_syntax::ast::*;

/// A formal parameter or local variable of a function.
#[derive(Clone, Debug)]
pub struct FuncVar {
    pub name: String,
    /// The declared type as written (`Real`, `Integer`, `Boolean`, ...).
    pub type_name: String,
    /// Dimensions; `None` for `:` or a size not known at compile time.
    pub dims: Vec<Option<usize>>,
    /// The default (inputs) or binding (outputs and locals).
    pub default: Option<Expr>,
}

/// A user function with an algorithm body.
#[derive(Clone, Debug)]
pub struct FlatFunction {
    /// Full dotted name, as calls in the flat model spell it.
    pub name: String,
    pub inputs: Vec<FuncVar>,
    pub outputs: Vec<FuncVar>,
    pub locals: Vec<FuncVar>,
    pub algorithm: Vec<Statement>,
    /// `external` functions have no body the back end can use.
    pub external: bool,
    pub origin: Span,
}

/// Global names of user functions called in `e`.
pub(crate) fn called_functions(e: &Expr, out: &mut Vec<String>) {
    match &e.kind {
        ExprKind::Call { func, args } => {
            if func.global {
                out.push(func.to_dotted().trim_start_matches('.').to_owned());
            }
            for a in &args.positional {
                called_functions(a, out);
            }
            for a in &args.named {
                called_functions(&a.value, out);
            }
        }
        ExprKind::Unary { operand, .. } => called_functions(operand, out),
        ExprKind::Binary { lhs, rhs, .. } => {
            called_functions(lhs, out);
            called_functions(rhs, out);
        }
        ExprKind::If {
            branches,
            otherwise,
        } => {
            for (c, v) in branches {
                called_functions(c, out);
                called_functions(v, out);
            }
            called_functions(otherwise, out);
        }
        ExprKind::Range { start, step, stop } => {
            called_functions(start, out);
            if let Some(s) = step {
                called_functions(s, out);
            }
            called_functions(stop, out);
        }
        ExprKind::Array(items) => items.iter().for_each(|x| called_functions(x, out)),
        ExprKind::Matrix(rows) => rows.iter().flatten().for_each(|x| called_functions(x, out)),
        ExprKind::Comprehension { body, .. } => called_functions(body, out),
        ExprKind::Tuple(items) => items
            .iter()
            .flatten()
            .for_each(|x| called_functions(x, out)),
        _ => {}
    }
}

pub(crate) fn statement_calls(s: &Statement, out: &mut Vec<String>) {
    match &s.kind {
        StatementKind::Assign { value, .. } => called_functions(value, out),
        StatementKind::MultiAssign { value, .. } => called_functions(value, out),
        StatementKind::Call(e) => called_functions(e, out),
        StatementKind::If {
            branches,
            otherwise,
        } => {
            for (c, body) in branches {
                called_functions(c, out);
                body.iter().for_each(|s| statement_calls(s, out));
            }
            otherwise.iter().for_each(|s| statement_calls(s, out));
        }
        StatementKind::When { branches } => {
            for (c, body) in branches {
                called_functions(c, out);
                body.iter().for_each(|s| statement_calls(s, out));
            }
        }
        StatementKind::For { indices, body } => {
            for i in indices {
                if let Some(r) = &i.range {
                    called_functions(r, out);
                }
            }
            body.iter().for_each(|s| statement_calls(s, out));
        }
        StatementKind::While { condition, body } => {
            called_functions(condition, out);
            body.iter().for_each(|s| statement_calls(s, out));
        }
        StatementKind::Return | StatementKind::Break => {}
    }
}

pub(crate) fn equation_calls(eq: &Equation, out: &mut Vec<String>) {
    match &eq.kind {
        EquationKind::Simple { lhs, rhs } => {
            called_functions(lhs, out);
            called_functions(rhs, out);
        }
        EquationKind::Call(e) => called_functions(e, out),
        EquationKind::Connect { .. } => {}
        EquationKind::If {
            branches,
            otherwise,
        } => {
            for (c, body) in branches {
                called_functions(c, out);
                body.iter().for_each(|e| equation_calls(e, out));
            }
            otherwise.iter().for_each(|e| equation_calls(e, out));
        }
        EquationKind::When { branches } => {
            for (c, body) in branches {
                called_functions(c, out);
                body.iter().for_each(|e| equation_calls(e, out));
            }
        }
        EquationKind::For { body, .. } => body.iter().for_each(|e| equation_calls(e, out)),
    }
}

impl Instantiator<'_, '_> {
    /// Collects every user function the model calls (transitively) into the model.
    pub(crate) fn collect_functions(&mut self) {
        let mut pending = Vec::new();
        for eq in self
            .model
            .equations
            .iter()
            .chain(&self.model.initial_equations)
        {
            equation_calls(eq, &mut pending);
        }
        for s in self
            .model
            .algorithms
            .iter()
            .chain(&self.model.initial_algorithms)
            .flatten()
        {
            statement_calls(s, &mut pending);
        }
        for v in &self.model.vars {
            if let Some(b) = &v.binding {
                called_functions(b, &mut pending);
            }
        }
        let mut done: Vec<String> = Vec::new();
        while let Some(name) = pending.pop() {
            if done.contains(&name) {
                continue;
            }
            done.push(name.clone());
            let parts: Vec<&str> = name.split('.').collect();
            let Some(Found::Class(c)) = self.tree.lookup_dotted(None, &parts, false) else {
                continue;
            };
            if self.tree.get(c).def.kind != ClassKind::Function {
                continue;
            }
            if let Some(f) = self.flat_function(c, &name) {
                for s in &f.algorithm {
                    statement_calls(s, &mut pending);
                }
                self.model.functions.push(f);
            }
        }
        self.model.functions.sort_by(|a, b| a.name.cmp(&b.name));
    }

    fn flat_function(&mut self, class: ClassId, name: &str) -> Option<FlatFunction> {
        let def = self.tree.get(class).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return None;
        };
        let scope = Scope {
            class,
            prefix: Vec::new(),
        };
        let mut f = FlatFunction {
            name: name.to_owned(),
            inputs: Vec::new(),
            outputs: Vec::new(),
            locals: Vec::new(),
            algorithm: Vec::new(),
            external: false,
            origin: def.name.span,
        };
        let mut local_names: Vec<String> = Vec::new();
        for e in &composition.elements {
            if let ElementKind::Component(cc) = &e.kind {
                local_names.extend(cc.components.iter().map(|d| d.name.text.to_string()));
            }
        }
        for e in &composition.elements {
            let ElementKind::Component(cc) = &e.kind else {
                continue;
            };
            for d in &cc.components {
                let dims = cc
                    .type_dims
                    .iter()
                    .chain(&d.dims)
                    .map(|s| match s {
                        Subscript::Colon(_) => None,
                        Subscript::Expr(x) => {
                            let x = self.function_expr(x, &scope, &mut local_names);
                            match eval::eval(&x, self, &mut Vec::new()) {
                                Ok(Value::Int(n)) if n >= 0 => Some(n as usize),
                                _ => None,
                            }
                        }
                    })
                    .collect();
                let default = d
                    .modification
                    .as_ref()
                    .and_then(|m| m.binding.as_ref())
                    .map(|b| self.function_expr(b, &scope, &mut local_names));
                let var = FuncVar {
                    name: d.name.text.to_string(),
                    type_name: cc.type_name.to_dotted(),
                    dims,
                    default,
                };
                match cc.prefix.causality {
                    Some(Causality::Input) => f.inputs.push(var),
                    Some(Causality::Output) => f.outputs.push(var),
                    None => f.locals.push(var),
                }
            }
        }
        for s in &composition.sections {
            if let Section::Algorithm(a) = s {
                for st in &a.statements {
                    let st = self.function_statement(st, &scope, &mut local_names);
                    f.algorithm.push(st);
                }
            }
        }
        f.external = composition.sections.is_empty() && f.algorithm.is_empty();
        Some(f)
    }
}
