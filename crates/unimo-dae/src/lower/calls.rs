//! Calls lowered: user functions inlined, scalar built-ins and special operators (`der`,
//! `pre`, `edge`, `smooth`, ...), reductions.

use super::{unsupported, Lowerer};
use crate::error::{DaeError, DaeResult};
use crate::expr::{Fn1, Fn2, Node, RelOp};
use crate::tensor::{self, Tensor};
use unimo_source::Span;
use unimo_syntax::ast::*;

impl Lowerer<'_> {
    pub(super) fn call(&mut self, func: &Name, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        let name = func.to_dotted().trim_start_matches('.').to_owned();
        if func.global {
            if let Some(f) = self.functions.get(name.as_str()).copied() {
                let mut outs = self.inline_call(f, args, span)?;
                return Ok(outs.swap_remove(0));
            }
            if let Some(t) = self.constructor(&name, args, span)? {
                return Ok(t);
            }
            // Builtin functions reached by a global name (`Modelica.Math.sin` style
            // wrappers are user functions; these are enumerations' `Integer` etc.).
            let last = func
                .parts
                .last()
                .map(|p| p.text.to_string())
                .unwrap_or_default();
            return self.builtin(&last, args, span).and_then(|r| {
                r.ok_or_else(|| DaeError::UnknownFunction {
                    name: name.to_string(),
                    span,
                })
            });
        }
        if unimo_builtins::is_unsupported(&name) {
            return Err(unsupported(
                format!(
                    "the built-in `{name}` (stream connectors, clocked and synchronous features, \
                     state machines and overconstrained connections are not implemented)"
                ),
                span,
            ));
        }
        match self.builtin(&name, args, span)? {
            Some(t) => Ok(t),
            None => Err(DaeError::UnknownFunction {
                name: name.to_string(),
                span,
            }),
        }
    }

    pub(crate) fn positional(
        &mut self,
        args: &CallArgs,
        k: usize,
        span: Span,
    ) -> DaeResult<Tensor> {
        match args.positional.get(k) {
            Some(e) => self.expr(e),
            None => Err(DaeError::ArgumentMissing {
                position: k + 1,
                span,
            }),
        }
    }

    /// Builtin operators and functions; `Ok(None)` when `name` is not one.
    fn builtin(&mut self, name: &str, args: &CallArgs, span: Span) -> DaeResult<Option<Tensor>> {
        if !args.iterators.is_empty() {
            return self.reduction(name, args, span).map(Some);
        }
        let nargs = args.positional.len();
        if let Some(f) = Fn1::from_name(name) {
            let x = self.positional(args, 0, span)?;
            return Ok(Some(x.map(|v| self.dae.arena.fn1(f, v))));
        }
        // A two-argument compiled form: `atan2`, `div`, `mod`, `rem`, and `min`/`max`
        // of two arguments (one argument is their reduction).
        let fn2 = Fn2::from_name(name)
            .filter(|f| nargs == 2 || unimo_builtins::Arity::Fixed(2) == f.entry().arity);
        if let Some(f) = fn2 {
            let a = self.positional(args, 0, span)?;
            let b = self.positional(args, 1, span)?;
            let ar = &mut self.dae.arena;
            let t = tensor::elementwise(ar, &a, &b, true, span, |x, p, q| x.fn2(f, p, q))?;
            return Ok(Some(t));
        }
        let t = match name {
            "der" => {
                let x = self.positional(args, 0, span)?;
                x.map(|v| self.time_derivative(v))
            }
            "pre" => {
                let x = self.positional(args, 0, span)?;
                let mut data = Vec::new();
                for &v in &x.data {
                    match self.dae.arena.node(v) {
                        Node::Var(s) => data.push(self.dae.arena.pre(s)),
                        Node::Const(_) => data.push(v),
                        _ => {
                            return Err(DaeError::NeedsVariable {
                                operator: "pre".to_owned(),
                                span,
                            })
                        }
                    }
                }
                Tensor { dims: x.dims, data }
            }
            "edge" | "change" => {
                let x = self.positional(args, 0, span)?;
                let mut data = Vec::new();
                for &v in &x.data {
                    let Node::Var(s) = self.dae.arena.node(v) else {
                        return Err(DaeError::NeedsVariable {
                            operator: name.to_string(),
                            span,
                        });
                    };
                    let p = self.dae.arena.pre(s);
                    data.push(if name == "edge" {
                        let np = self.dae.arena.not(p);
                        self.dae.arena.and(v, np)
                    } else {
                        self.dae.arena.rel(RelOp::Ne, v, p)
                    });
                }
                Tensor { dims: x.dims, data }
            }
            "initial" => Tensor::scalar(self.a().initial()),
            "collisionBody" => self.collision_body(args, span)?,
            "collisionGaps" => self.collision_gaps(args, span)?,
            "terminal" => {
                self.dae.uses_terminal = true;
                Tensor::scalar(self.a().terminal())
            }
            "noEvent" => {
                let x = self.positional(args, 0, span)?;
                x.map(|v| self.dae.arena.no_event(v))
            }
            "smooth" => self.positional(args, 1, span)?,
            "homotopy" => self.homotopy(args, span)?,
            "sample" => {
                let a = self.positional(args, 0, span)?.as_scalar(span)?;
                let b = self.positional(args, 1, span)?.as_scalar(span)?;
                Tensor::scalar(self.a().sample(a, b))
            }
            "semiLinear" => self.semi_linear(args, span)?,
            "Integer" | "Real" | "integer_of_enum" => self.positional(args, 0, span)?,
            "abs_" => return Ok(None),
            _ => return self.array_builtin(name, args, span),
        };
        Ok(Some(t))
    }

    /// `homotopy(actual, simplified)`: `simplified` while initialization solves the
    /// start of the continuation (`Node::HomotopyStart`), else `actual`.
    fn homotopy(&mut self, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        let named = |n: &str| args.named.iter().find(|a| a.name.text == n);
        let actual = match named("actual") {
            Some(a) => self.expr(&a.value)?,
            None => self.positional(args, 0, span)?,
        };
        let simplified = match named("simplified") {
            Some(a) => self.expr(&a.value)?,
            None if args.positional.len() > 1 => self.positional(args, 1, span)?,
            None => return Ok(actual),
        };
        if simplified.dims != actual.dims {
            return Ok(actual);
        }
        let flag = self.a().homotopy_start();
        let mut simplified = simplified.data.into_iter();
        Ok(actual.map(|a| {
            let s = simplified.next().unwrap_or(a);
            self.dae.arena.if_(flag, s, a)
        }))
    }

    /// `semiLinear(x, p, n)`: `p*x` for `x >= 0`, else `n*x`.
    fn semi_linear(&mut self, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        let x = self.positional(args, 0, span)?.as_scalar(span)?;
        let p = self.positional(args, 1, span)?.as_scalar(span)?;
        let n = self.positional(args, 2, span)?.as_scalar(span)?;
        let ar = self.a();
        let zero = ar.zero();
        let c = ar.rel(RelOp::Ge, x, zero);
        let px = ar.mul(p, x);
        let nx = ar.mul(n, x);
        Ok(Tensor::scalar(ar.if_(c, px, nx)))
    }

    /// `collisionGaps(...)`: the model's one collision world and its two gap outputs.
    fn collision_gaps(&mut self, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        let mut flat = Vec::new();
        for e in &args.positional {
            flat.extend(self.expr(e)?.data);
        }
        let named = crate::dae::CollisionWorldArgs::from_flat(&flat);
        let Some(named) = named.filter(|_| self.dae.collision_world.is_none()) else {
            return Err(DaeError::CollisionWorldArguments {
                count: crate::dae::COLLISION_WORLD_ARGS,
                span,
            });
        };
        self.dae.collision_world = Some(crate::dae::CollisionWorld { args: named, span });
        let g = crate::dae::COLLISION_GAPS_SITE;
        let data = (0..2).map(|k| self.dae.arena.external(g, k)).collect();
        Ok(Tensor {
            dims: vec![2],
            data,
        })
    }

    /// `collisionBody(...)`: its arguments by name in a new collision site (its shape and
    /// law codes checked when constant), and the six outputs of the site (force, torque).
    fn collision_body(&mut self, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        // Every argument, flattened in order; the runtime reads them by position
        // (see `unimo_runtime::collision`).
        let mut flat = Vec::new();
        for e in &args.positional {
            flat.extend(self.expr(e)?.data);
        }
        let Some(named) = crate::dae::CollisionBodyArgs::from_flat(&flat) else {
            return Err(DaeError::CollisionBodyArity {
                expected: crate::dae::COLLISION_BODY_ARGS,
                given: flat.len(),
                span,
            });
        };
        // The codes of the shape and the damping law (the library passes its
        // enumerations; a direct call may pass anything).
        use crate::collision_args::{LawCode, ShapeCode};
        let shape_ok = |x: f64| ShapeCode::from_value(x).is_some();
        let law_ok = |x: f64| LawCode::from_value(x).is_some();
        let checks = [
            (
                named.shape,
                "shape",
                ShapeCode::ALL.len(),
                &shape_ok as &dyn Fn(f64) -> bool,
            ),
            (named.law, "damping law", LawCode::ALL.len(), &law_ok),
        ];
        for (arg, what, count, valid) in checks {
            if let Some(code) = self.const_value(arg) {
                if !valid(code) {
                    return Err(DaeError::CollisionCode {
                        code,
                        what,
                        count,
                        span,
                    });
                }
            }
        }
        let site = self.dae.collision.len() as u32;
        self.dae
            .collision
            .push(crate::dae::CollisionBody { args: named, span });
        let data = (0..6).map(|k| self.dae.arena.external(site, k)).collect();
        Ok(Tensor {
            dims: vec![6],
            data,
        })
    }

    /// `sum(e for i in r)` and friends.
    fn reduction(&mut self, name: &str, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        let body = args
            .positional
            .first()
            .ok_or(DaeError::ReductionWithoutExpression { span })?;
        let items = self.comprehension(body, &args.iterators)?;
        let stacked = Tensor::stack(items, span)?;
        match name {
            "sum" | "product" | "min" | "max" => self.reduce(name, &stacked, span),
            "array" => Ok(stacked),
            _ => Err(unsupported(format!("`{name}(... for ...)`"), span)),
        }
    }

    pub(super) fn reduce(&mut self, name: &str, t: &Tensor, span: Span) -> DaeResult<Tensor> {
        let ar = &mut self.dae.arena;
        let r = match name {
            "sum" => t.data.iter().fold(ar.zero(), |acc, &x| ar.add(acc, x)),
            "product" => t.data.iter().fold(ar.one(), |acc, &x| ar.mul(acc, x)),
            "min" | "max" => {
                let f = Fn2::from_name(name).expect("min and max have a compiled form");
                let Some((&first, rest)) = t.data.split_first() else {
                    return Err(DaeError::ReductionOfEmpty {
                        function: name.to_string(),
                        span,
                    });
                };
                rest.iter().fold(first, |acc, &x| ar.fn2(f, acc, x))
            }
            _ => unreachable!("reduce is called for sum, product, min and max"),
        };
        Ok(Tensor::scalar(r))
    }

    pub(super) fn dims_args(&mut self, args: &CallArgs, from: usize) -> DaeResult<Vec<usize>> {
        let mut dims = Vec::new();
        for e in &args.positional[from.min(args.positional.len())..] {
            let n = self.constant_int(e)?;
            dims.push(n.max(0) as usize);
        }
        Ok(dims)
    }
}
