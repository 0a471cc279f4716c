//! Compile-time calls of user functions: binds the arguments, runs the algorithm
//! section statement by statement, returns the first output (spec 12.4).

use crate::eval::{self, Arguments, Env, EvalError, Value};
use crate::instantiate::Instantiator;
use crate::lookup::Found;
use crate::modif::Scope;
use rustc_hash::FxHashMap as HashMap;
use unimo_source::Span;
use unimo_syntax::ast::*;

/// Statements executed before a call is given up (runaway `while` loops).
const MAX_STEPS: usize = 1_000_000;
/// Nested calls before a call is given up (runaway recursion).
const MAX_CALL_DEPTH: usize = 64;

/// The local variables of one call, seen by the evaluator.
struct Frame<'i, 't, 'p> {
    inst: &'i mut Instantiator<'t, 'p>,
    locals: HashMap<String, Value>,
}

impl Env for Frame<'_, '_, '_> {
    fn var(&mut self, key: &str, span: Span) -> Result<Value, EvalError> {
        match self.locals.get(key) {
            Some(v) => Ok(v.clone()),
            None => match record_field_slot(&mut self.locals, key) {
                Some(v) => Ok(v.clone()),
                None => self.inst.var(key, span),
            },
        }
    }

    fn call(&mut self, name: &str, args: Arguments, span: Span) -> Result<Value, EvalError> {
        self.inst.call(name, args, span)
    }
}

enum Flow {
    Next,
    Break,
    Return,
}

fn not_constant(span: Span, what: String) -> EvalError {
    EvalError::NotConstant { span, what }
}

impl Instantiator<'_, '_> {
    pub(crate) fn call_function(
        &mut self,
        name: &str,
        args: Arguments,
        span: Span,
    ) -> Result<Value, EvalError> {
        if self.call_depth >= MAX_CALL_DEPTH {
            return Err(EvalError::Unsupported {
                span,
                what: format!("calls nested deeper than {MAX_CALL_DEPTH} in `{name}`"),
            });
        }
        let parts: Vec<&str> = crate::flat::split_name(name);
        let Some(Found::Class(f)) = self.tree.lookup_dotted(None, &parts, false) else {
            return Err(not_constant(span, format!("a call of `{name}`")));
        };
        if self.is_record(f) {
            return self.construct_record(f, args, span);
        }
        let def = self.tree.get(f).def.clone();
        let ClassBody::Long { composition, .. } = &def.body else {
            return Err(not_constant(span, format!("a call of `{name}`")));
        };
        if def.kind != ClassKind::Function {
            return Err(not_constant(
                span,
                format!("`{name}`, which is not a function"),
            ));
        }
        let scope = Scope {
            class: f,
            prefix: std::sync::Arc::from([]),
        };
        let mut locals: HashMap<String, Value> = HashMap::default();
        let mut inputs = Vec::new();
        let mut outputs = Vec::new();
        let mut defaults = Vec::new();
        for e in &composition.elements {
            let ElementKind::Component(cc) = &e.kind else {
                continue;
            };
            for d in &cc.components {
                let n = d.name.text.to_string();
                match cc.prefix.causality {
                    Some(Causality::Input) => inputs.push(n.clone()),
                    Some(Causality::Output) => outputs.push(n.clone()),
                    None => {}
                }
                if let Some(b) = d.modification.as_ref().and_then(|m| m.binding.as_ref()) {
                    defaults.push((n, b.clone()));
                }
            }
        }
        for (k, v) in args.positional.into_iter().enumerate() {
            let Some(n) = inputs.get(k) else {
                return Err(EvalError::Unsupported {
                    span,
                    what: format!("too many arguments for `{name}`"),
                });
            };
            locals.insert(n.clone(), v);
        }
        for (n, v) in args.named {
            locals.insert(n, v);
        }
        self.call_depth += 1;
        let r = self.run_body(&scope, composition, &mut locals, defaults, span);
        self.call_depth -= 1;
        r?;
        let out = outputs.first().ok_or_else(|| EvalError::Unsupported {
            span,
            what: format!("`{name}` has no output"),
        })?;
        locals.remove(out).ok_or_else(|| EvalError::Unsupported {
            span,
            what: format!("`{name}` did not assign its output `{out}`"),
        })
    }

    /// A record constructor call (spec 12.6): the arguments in the order of the
    /// constructor's inputs, the other fields from their bindings.
    fn construct_record(
        &mut self,
        class: crate::tree::ClassId,
        args: Arguments,
        span: Span,
    ) -> Result<Value, EvalError> {
        let fields = self.record_fields(class);
        let record = self.tree.full_name(class);
        let inputs: Vec<&crate::records::Field> = fields.iter().filter(|f| f.input).collect();
        if args.positional.len() > inputs.len() {
            return Err(EvalError::Unsupported {
                span,
                what: format!("too many arguments for record `{record}`"),
            });
        }
        let mut locals: HashMap<String, Value> = HashMap::default();
        for (f, v) in inputs.iter().zip(args.positional) {
            locals.insert(f.name.to_string(), v);
        }
        for (n, v) in args.named {
            if !inputs.iter().any(|f| f.name == n.as_str()) {
                return Err(EvalError::Unsupported {
                    span,
                    what: format!("record `{record}` has no field `{n}` to construct"),
                });
            }
            locals.insert(n, v);
        }
        let mut out = Vec::with_capacity(fields.len());
        for f in &fields {
            let v = match (locals.get(f.name.as_str()), &f.default) {
                (Some(v), _) if f.input => v.clone(),
                (_, Some(b)) => {
                    let scope = Scope {
                        class: f.owner,
                        prefix: std::sync::Arc::from([]),
                    };
                    let v = self.eval_local(b, &scope, &mut locals)?;
                    locals.insert(f.name.to_string(), v.clone());
                    v
                }
                _ => {
                    return Err(not_constant(
                        span,
                        format!("field `{}` of record `{record}`, not given", f.name),
                    ))
                }
            };
            out.push((f.name.to_string(), v));
        }
        Ok(Value::Record(record, out))
    }

    fn run_body(
        &mut self,
        scope: &Scope,
        composition: &Composition,
        locals: &mut HashMap<String, Value>,
        defaults: Vec<(String, Expr)>,
        span: Span,
    ) -> Result<(), EvalError> {
        // Defaults of inputs not given, and bindings of outputs and locals, in order.
        for (n, b) in defaults {
            if !locals.contains_key(&n) {
                let v = self.eval_local(&b, scope, locals)?;
                locals.insert(n, v);
            }
        }
        let mut steps = 0;
        for s in &composition.sections {
            if let Section::Algorithm(al) = s {
                if let Flow::Return = self.exec(&al.statements, scope, locals, &mut steps, span)? {
                    break;
                }
            }
        }
        Ok(())
    }

    fn eval_local(
        &mut self,
        e: &Expr,
        scope: &Scope,
        locals: &mut HashMap<String, Value>,
    ) -> Result<Value, EvalError> {
        let flat = self.expr_in_function(e, scope);
        let mut frame = Frame {
            inst: self,
            locals: std::mem::take(locals),
        };
        let r = eval::eval(&flat, &mut frame, &mut Vec::new());
        *locals = frame.locals;
        r
    }

    fn exec(
        &mut self,
        stmts: &[Statement],
        scope: &Scope,
        locals: &mut HashMap<String, Value>,
        steps: &mut usize,
        span: Span,
    ) -> Result<Flow, EvalError> {
        for st in stmts {
            *steps += 1;
            if *steps > MAX_STEPS {
                return Err(EvalError::Unsupported {
                    span,
                    what: format!("a function call that runs more than {MAX_STEPS} statements"),
                });
            }
            match &st.kind {
                StatementKind::Assign { target, value } => {
                    self.exec_assign(st, (target, value), scope, locals)?
                }
                StatementKind::If {
                    branches,
                    otherwise,
                } => {
                    let mut taken = None;
                    for (c, body) in branches {
                        if self
                            .eval_local(c, scope, locals)?
                            .as_bool()
                            .unwrap_or(false)
                        {
                            taken = Some(body);
                            break;
                        }
                    }
                    let flow = self.exec(taken.unwrap_or(otherwise), scope, locals, steps, span)?;
                    if !matches!(flow, Flow::Next) {
                        return Ok(flow);
                    }
                }
                StatementKind::For { indices, body } => {
                    if let Flow::Return =
                        self.exec_for(st, (indices, body), scope, locals, steps, span)?
                    {
                        return Ok(Flow::Return);
                    }
                }
                StatementKind::While { condition, body } => {
                    while self
                        .eval_local(condition, scope, locals)?
                        .as_bool()
                        .unwrap_or(false)
                    {
                        match self.exec(body, scope, locals, steps, span)? {
                            Flow::Next => {}
                            Flow::Break => break,
                            Flow::Return => return Ok(Flow::Return),
                        }
                        *steps += 1;
                        if *steps > MAX_STEPS {
                            return Err(EvalError::Unsupported {
                                span,
                                what: format!("a loop that runs more than {MAX_STEPS} steps"),
                            });
                        }
                    }
                }
                StatementKind::Break => return Ok(Flow::Break),
                StatementKind::Return => return Ok(Flow::Return),
                // `assert(condition, message)` in a function evaluated at compile time:
                // checked here (a failing one stops the evaluation with its message).
                StatementKind::Call(Expr {
                    kind: ExprKind::Call { func, args },
                    ..
                }) if func.to_dotted() == "assert" && !args.positional.is_empty() => {
                    self.exec_assert(st, args, scope, locals)?
                }
                StatementKind::Call(_)
                | StatementKind::MultiAssign { .. }
                | StatementKind::When { .. } => {
                    return Err(EvalError::Unsupported {
                        span: st.span,
                        what: "this statement at compile time".into(),
                    });
                }
            }
        }
        Ok(Flow::Next)
    }

    /// `assert(condition, message)` in a function evaluated at compile time: checked
    /// here (a failing one stops the evaluation with its message).
    fn exec_assert(
        &mut self,
        st: &Statement,
        args: &CallArgs,
        scope: &Scope,
        locals: &mut HashMap<String, Value>,
    ) -> Result<(), EvalError> {
        let holds = self
            .eval_local(&args.positional[0], scope, locals)?
            .as_bool()
            .ok_or_else(|| EvalError::Unsupported {
                span: st.span,
                what: "an assertion whose condition is not Boolean".into(),
            })?;
        if !holds {
            let message = match args.positional.get(1).map(|m| &m.kind) {
                Some(ExprKind::String(text)) => text.to_string(),
                _ => "an assertion".into(),
            };
            return Err(EvalError::Unsupported {
                span: st.span,
                what: format!("this call: its assertion \"{message}\" fails"),
            });
        }
        Ok(())
    }

    /// A `for` loop over the values of its (first) range: `Flow::Return` when its body
    /// returns, else `Flow::Next`.
    fn exec_for(
        &mut self,
        st: &Statement,
        (indices, body): (&[ForIndex], &[Statement]),
        scope: &Scope,
        locals: &mut HashMap<String, Value>,
        steps: &mut usize,
        span: Span,
    ) -> Result<Flow, EvalError> {
        let Some(first) = indices.first() else {
            return Ok(Flow::Next);
        };
        let range = match &first.range {
            Some(r) => self.eval_local(r, scope, locals)?,
            None => {
                return Err(EvalError::Unsupported {
                    span: st.span,
                    what: "a `for` without range".into(),
                })
            }
        };
        let Value::Array(values) = range else {
            return Err(EvalError::Unsupported {
                span: st.span,
                what: "a `for` range that is not an array".into(),
            });
        };
        for v in values {
            locals.insert(first.name.text.to_string(), v);
            match self.exec(body, scope, locals, steps, span)? {
                Flow::Next => {}
                Flow::Break => break,
                Flow::Return => return Ok(Flow::Return),
            }
        }
        Ok(Flow::Next)
    }

    /// An assignment to a local, whole or one element.
    fn exec_assign(
        &mut self,
        st: &Statement,
        (target, value): (&ComponentRef, &Expr),
        scope: &Scope,
        locals: &mut HashMap<String, Value>,
    ) -> Result<(), EvalError> {
        let v = self.eval_local(value, scope, locals)?;
        let name = target.to_dotted();
        let subs = target
            .parts
            .last()
            .map(|p| p.subscripts.clone())
            .unwrap_or_default();
        if subs.is_empty() {
            if !locals.contains_key(&name) {
                if let Some(slot) = record_field_slot(locals, &name) {
                    *slot = v;
                    return Ok(());
                }
            }
            locals.insert(name, v);
        } else {
            let mut idx = Vec::new();
            for s in &subs {
                let Subscript::Expr(e) = s else {
                    return Err(EvalError::Unsupported {
                        span: st.span,
                        what: "assignment to a slice".into(),
                    });
                };
                let i = self.eval_local(e, scope, locals)?.as_int().ok_or_else(|| {
                    EvalError::Unsupported {
                        span: st.span,
                        what: "a non-Integer index".into(),
                    }
                })?;
                idx.push(i);
            }
            let slot = record_field_slot(locals, &name)
                .ok_or_else(|| not_constant(st.span, format!("`{name}` before it has a value")))?;
            set_element(slot, &idx, v).ok_or_else(|| EvalError::Unsupported {
                span: st.span,
                what: "an index out of bounds".into(),
            })?;
        }
        Ok(())
    }
}

/// The local `key` names, or the field of a record local it names (`R.T`).
fn record_field_slot<'l>(
    locals: &'l mut HashMap<String, Value>,
    key: &str,
) -> Option<&'l mut Value> {
    if locals.contains_key(key) {
        return locals.get_mut(key);
    }
    let mut parts = key.split('.');
    let mut v = locals.get_mut(parts.next()?)?;
    for p in parts {
        let Value::Record(_, fields) = v else {
            return None;
        };
        v = &mut fields.iter_mut().find(|(n, _)| n == p)?.1;
    }
    Some(v)
}

fn set_element(v: &mut Value, idx: &[i64], x: Value) -> Option<()> {
    let Some((first, rest)) = idx.split_first() else {
        *v = x;
        return Some(());
    };
    let Value::Array(items) = v else { return None };
    let slot = items.get_mut(usize::try_from(*first - 1).ok()?)?;
    set_element(slot, rest, x)
}
