//! `delay(e, delayTime)` and `delay(e, delayTime, delayMax)` (spec 3.7.4.1): the value
//! of `e` at `time - delayTime`, and `e` at the start time before `time.start +
//! delayTime`. Lowering gives each call a site `k`: a hidden variable `$delayK = e`
//! (an ordinary equation, so that `e`'s relations are zero crossings and its jumps
//! happen at events; alias elimination removes it when `e` is a variable), a
//! [`DelaySite`] holding its value as an expression (the runtime records it after
//! every accepted step, at initialization and before and after every event), and the
//! node `Ext(Delay, [k, delayMax, time - delayTime, d])`, which reads the recorded
//! history (`d` is the delay time when it is a parameter expression, else NaN: the
//! simulator's steps then end where the delay moves a discontinuity of `e`). The node names no unknown, so a delayed value is known from the past:
//! no algebraic loop runs through it (a transmission line's two ends).
//!
//! Without `delayMax` the delay time must be a parameter expression (it then is its
//! own `delayMax`); `delayMax` must be one in any case; both must not be negative. A
//! varying delay time is held in `[0, delayMax]`.

use crate::dae::{Equation, Scalar, ScalarKind, ScalarType};
use crate::error::{DaeError, DaeResult};
use crate::expr::{ExprId, Fn2, Node};
use crate::external::ExtFn;
use crate::lower::Lowerer;
use crate::tensor::Tensor;
use unimo_source::Span;
use unimo_syntax::ast::CallArgs;

/// One `delay` call: the expression of the delayed value `e` (in terms of the DAE's
/// scalars; rewritten by alias elimination like the equations).
#[derive(Clone, Debug)]
pub struct DelaySite {
    pub input: ExprId,
    pub span: Span,
}

impl Lowerer<'_> {
    /// `delay(e, delayTime[, delayMax])`, elementwise in `e`.
    pub(crate) fn delay_call(&mut self, args: &CallArgs, span: Span) -> DaeResult<Tensor> {
        let n = args.positional.len();
        if !(2..=3).contains(&n) || !args.named.is_empty() {
            return Err(DaeError::DelayArguments {
                what: "takes two or three positional arguments: `delay(e, delayTime)` or \
                       `delay(e, delayTime, delayMax)`",
                span,
            });
        }
        let e = self.positional(args, 0, span)?;
        let delay_time = self.scalar(&args.positional[1])?;
        let delay_max = match args.positional.get(2) {
            Some(m) => {
                let m_span = m.span;
                let m = self.scalar(m)?;
                if !self.is_parameter_expr(m) {
                    return Err(DaeError::DelayArguments {
                        what: "needs a parameter expression as `delayMax`",
                        span: m_span,
                    });
                }
                m
            }
            None => {
                if !self.is_parameter_expr(delay_time) {
                    return Err(DaeError::DelayTimeNotParameter {
                        span: args.positional[1].span,
                    });
                }
                delay_time
            }
        };
        let (dt, dmax) = (self.const_value(delay_time), self.const_value(delay_max));
        if dt.is_some_and(|d| d < 0.0) || dmax.is_some_and(|d| d < 0.0) {
            return Err(DaeError::DelayArguments {
                what: "needs a delay time and a `delayMax` that are not negative",
                span,
            });
        }
        if let (Some(dt), Some(dmax)) = (dt, dmax) {
            if dt > dmax {
                return Err(DaeError::DelayArguments {
                    what: "needs a delay time not larger than `delayMax`",
                    span,
                });
            }
        }
        let time = self.dae.arena.time();
        // A varying delay time is held in [0, delayMax] (without events).
        let held = if self.is_parameter_expr(delay_time) {
            delay_time
        } else {
            let a = &mut self.dae.arena;
            let zero = a.zero();
            let below = a.fn2(Fn2::Min, delay_time, delay_max);
            a.fn2(Fn2::Max, below, zero)
        };
        let at = self.dae.arena.sub(time, held);
        // A constant delay: the runtime's steps stop where it moves a discontinuity.
        let fixed = if self.is_parameter_expr(delay_time) {
            delay_time
        } else {
            self.dae.arena.constant(f64::NAN)
        };
        let data = e
            .data
            .iter()
            .map(|&x| self.delay_site(x, [delay_max, at, fixed], span))
            .collect();
        Ok(Tensor { dims: e.dims, data })
    }

    /// One scalar delay of `x`: its hidden variable, site and lookup node.
    fn delay_site(&mut self, x: ExprId, ops: [ExprId; 3], span: Span) -> ExprId {
        let k = self.dae.delays.len();
        let mut s = Scalar::new(
            format!("$delay{}", k + 1),
            ScalarKind::Continuous,
            ScalarType::Real,
            span,
        );
        s.description = Some("the value `delay` records".into());
        let v = self.dae.add_scalar(s);
        let lhs = self.dae.arena.var(v);
        self.dae.equations.push(Equation {
            lhs,
            rhs: x,
            origin: span,
            derivative_of: None,
        });
        self.dae.delays.push(DelaySite { input: lhs, span });
        let site = self.dae.arena.constant(k as f64);
        self.ext_node(ExtFn::Delay, &[site, ops[0], ops[1], ops[2]])
    }

    /// Whether `e` is a parameter expression: it reads only parameters and constants,
    /// and not time.
    fn is_parameter_expr(&self, e: ExprId) -> bool {
        let a = &self.dae.arena;
        let fixed = a.vars(e).into_iter().all(|s| {
            matches!(
                self.dae.scalar(s).kind,
                ScalarKind::Parameter | ScalarKind::Constant
            )
        });
        let mut stack = vec![e];
        let mut seen = rustc_hash::FxHashSet::default();
        while let Some(x) = stack.pop() {
            if !seen.insert(x) {
                continue;
            }
            if matches!(a.node(x), Node::Time | Node::Initial | Node::Terminal) {
                return false;
            }
            stack.extend(a.children(x));
        }
        fixed
    }
}
