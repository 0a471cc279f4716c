//! Symbolic differentiation: with respect to time (for index reduction and `der` of
//! expressions) and with respect to a variable (Jacobians, solvability), for every
//! node, and `solve` for equations linear in one variable.

use crate::expr::{ExprArena, ExprId, Fn1, Fn2, Node, ScalarId};
use rustc_hash::FxHashMap as HashMap;

/// What a derivative needs to know about the leaves.
pub struct Seed<'a> {
    /// The derivative of a variable, `None` meaning zero (a parameter, a discrete
    /// variable, or not the variable differentiated for).
    pub var: &'a mut dyn FnMut(&mut ExprArena, ScalarId) -> Option<ExprId>,
    /// d(time)/d(whatever): 1 for time derivatives, 0 for partial derivatives.
    pub time: f64,
}

/// The derivative of `e` under `seed`, memoized over the shared graph.
pub fn derivative(
    arena: &mut ExprArena,
    e: ExprId,
    seed: &mut Seed<'_>,
    memo: &mut HashMap<ExprId, ExprId>,
) -> ExprId {
    if let Some(&d) = memo.get(&e) {
        return d;
    }
    let d = derivative_node(arena, e, seed, memo);
    memo.insert(e, d);
    d
}

fn derivative_node(
    a: &mut ExprArena,
    e: ExprId,
    seed: &mut Seed<'_>,
    memo: &mut HashMap<ExprId, ExprId>,
) -> ExprId {
    let mut d = |a: &mut ExprArena, x: ExprId, seed: &mut Seed<'_>| derivative(a, x, seed, memo);
    match a.node(e) {
        Node::Const(_)
        | Node::Pre(_)
        | Node::Initial
        | Node::Terminal
        | Node::HomotopyStart
        | Node::Rel(..)
        | Node::And(..)
        | Node::Or(..)
        | Node::Not(_)
        | Node::Sample(..) => a.zero(),
        Node::Var(s) => match (seed.var)(a, s) {
            Some(x) => x,
            None => a.zero(),
        },
        Node::Time => a.constant(seed.time),
        // An external output has no symbolic operands: its partial derivatives are zero
        // (the runtime differentiates such models numerically); a time derivative is
        // unknown, so it evaluates to NaN and shows up as an evaluation error.
        Node::External(..) => {
            if seed.time == 0.0 {
                a.zero()
            } else {
                a.constant(f64::NAN)
            }
        }
        Node::Ext(f, ops) => external_derivative(a, f, ops, seed, memo),
        Node::Add(x, y) => {
            let (dx, dy) = operand_derivatives(a, (x, y), seed, memo);
            a.add(dx, dy)
        }
        Node::Neg(x) => {
            let dx = d(a, x, seed);
            a.neg(dx)
        }
        Node::Mul(x, y) => {
            let (dx, dy) = operand_derivatives(a, (x, y), seed, memo);
            let l = a.mul(dx, y);
            let r = a.mul(x, dy);
            a.add(l, r)
        }
        Node::Div(x, y) => {
            // (dx*y - x*dy) / y^2  written as dx/y - x*dy/y^2
            let (dx, dy) = operand_derivatives(a, (x, y), seed, memo);
            let first = a.div(dx, y);
            let xdy = a.mul(x, dy);
            let two = a.constant(2.0);
            let y2 = a.pow(y, two);
            let second = a.div(xdy, y2);
            a.sub(first, second)
        }
        Node::Pow(x, y) => {
            let (dx, dy) = operand_derivatives(a, (x, y), seed, memo);
            power_derivative(a, e, (x, y), (dx, dy))
        }
        Node::Fn1(f, x) => {
            let dx = d(a, x, seed);
            if a.as_const(dx) == Some(0.0) {
                return a.zero();
            }
            let inner = fn1_derivative(a, f, x, e);
            a.mul(inner, dx)
        }
        Node::Fn2(f, x, y) => {
            let (dx, dy) = operand_derivatives(a, (x, y), seed, memo);
            fn2_derivative(a, f, x, y, dx, dy)
        }
        Node::If(c, x, y) => {
            let (dx, dy) = operand_derivatives(a, (x, y), seed, memo);
            a.if_(c, dx, dy)
        }
        Node::NoEvent(x) => {
            let dx = d(a, x, seed);
            a.no_event(dx)
        }
    }
}

/// The derivatives of the operands `x` and `y` of a node with two, `x`'s first.
fn operand_derivatives(
    a: &mut ExprArena,
    (x, y): (ExprId, ExprId),
    seed: &mut Seed<'_>,
    memo: &mut HashMap<ExprId, ExprId>,
) -> (ExprId, ExprId) {
    let dx = derivative(a, x, seed, memo);
    let dy = derivative(a, y, seed, memo);
    (dx, dy)
}

/// The derivative of a table's value: its slope times the derivative of its input (the
/// last operand); the handle and column are constants. Piecewise constant functions
/// (bounds, next event) have derivative zero.
fn external_derivative(
    a: &mut ExprArena,
    f: crate::external::ExtFn,
    ops: [ExprId; 4],
    seed: &mut Seed<'_>,
    memo: &mut HashMap<ExprId, ExprId>,
) -> ExprId {
    let [_, x, y, _] = ops;
    let input = if f.arity() == 2 { y } else { x };
    match f.slope() {
        Some(slope) if f.arity() == 2 => {
            let dinput = derivative(a, input, seed, memo);
            let s = a.intern(Node::Ext(slope, ops));
            a.mul(s, dinput)
        }
        // The slope of a slope is not provided: an index reduction that needs
        // it evaluates to NaN and fails visibly.
        _ if matches!(
            f,
            crate::external::ExtFn::Table1DSlope
                | crate::external::ExtFn::TimeTableSlope
                | crate::external::ExtFn::DelaySlope
        ) =>
        {
            let dinput = derivative(a, input, seed, memo);
            if a.as_const(dinput) == Some(0.0) {
                a.zero()
            } else {
                a.constant(f64::NAN)
            }
        }
        _ => a.zero(),
    }
}

/// The derivative of `e = x^y` given `dx` and `dy`: `n * x^(n-1) * dx` for a constant
/// exponent `n`, else `x^y * (dy*log(x) + y*dx/x)`.
fn power_derivative(
    a: &mut ExprArena,
    e: ExprId,
    (x, y): (ExprId, ExprId),
    (dx, dy): (ExprId, ExprId),
) -> ExprId {
    if let Some(n) = a.as_const(y) {
        // n * x^(n-1) * dx
        let n1 = a.constant(n - 1.0);
        let p = a.pow(x, n1);
        let c = a.constant(n);
        let m = a.mul(c, p);
        a.mul(m, dx)
    } else {
        // x^y * (dy*log(x) + y*dx/x)
        let lx = a.fn1(Fn1::Log, x);
        let t1 = a.mul(dy, lx);
        let ydx = a.mul(y, dx);
        let t2 = a.div(ydx, x);
        let s = a.add(t1, t2);
        a.mul(e, s)
    }
}

/// f'(x) for `e = f(x)`, by the table's rule for `f` (`unimo_builtins::Derivative`).
fn fn1_derivative(a: &mut ExprArena, f: Fn1, x: ExprId, e: ExprId) -> ExprId {
    use unimo_builtins::Derivative as D;
    let one = a.one();
    let two = a.constant(2.0);
    match f.derivative() {
        D::Cos => a.fn1(Fn1::Cos, x),
        D::NegSin => {
            let s = a.fn1(Fn1::Sin, x);
            a.neg(s)
        }
        D::OnePlusSquareOfValue => {
            let t2 = a.pow(e, two);
            a.add(one, t2)
        }
        rule @ (D::InvSqrtOneMinusSquare | D::NegInvSqrtOneMinusSquare) => {
            let x2 = a.pow(x, two);
            let r = a.sub(one, x2);
            let s = a.fn1(Fn1::Sqrt, r);
            let q = a.div(one, s);
            if rule == D::InvSqrtOneMinusSquare {
                q
            } else {
                a.neg(q)
            }
        }
        D::InvOnePlusSquare => {
            let x2 = a.pow(x, two);
            let r = a.add(one, x2);
            a.div(one, r)
        }
        D::Cosh => a.fn1(Fn1::Cosh, x),
        D::Sinh => a.fn1(Fn1::Sinh, x),
        D::OneMinusSquareOfValue => {
            let t2 = a.pow(e, two);
            a.sub(one, t2)
        }
        D::Value => e,
        D::Reciprocal => a.div(one, x),
        D::ReciprocalLn10 => {
            let ln10 = a.constant(std::f64::consts::LN_10);
            let m = a.mul(ln10, x);
            a.div(one, m)
        }
        D::HalfReciprocalOfValue => {
            let m = a.mul(two, e);
            a.div(one, m)
        }
        D::Sign => a.fn1(Fn1::Sign, x),
        D::Zero => a.zero(),
        rule => unreachable!("`{}` has the rule {rule:?} of another arity", f.name()),
    }
}

/// The total derivative of `f(x, y)` from dx and dy, by the table's rule for `f`.
fn fn2_derivative(
    a: &mut ExprArena,
    f: Fn2,
    x: ExprId,
    y: ExprId,
    dx: ExprId,
    dy: ExprId,
) -> ExprId {
    use unimo_builtins::Derivative as D;
    match f.derivative() {
        D::Atan2 => {
            // atan2(x, y): (y dx - x dy) / (x^2 + y^2)
            let two = a.constant(2.0);
            let ydx = a.mul(y, dx);
            let xdy = a.mul(x, dy);
            let num = a.sub(ydx, xdy);
            let x2 = a.pow(x, two);
            let y2 = a.pow(y, two);
            let den = a.add(x2, y2);
            a.div(num, den)
        }
        D::MinSelect => {
            let c = a.rel(crate::expr::RelOp::Lt, x, y);
            a.if_(c, dx, dy)
        }
        D::MaxSelect => {
            let c = a.rel(crate::expr::RelOp::Gt, x, y);
            a.if_(c, dx, dy)
        }
        D::Mod => {
            let q = a.div(x, y);
            let fl = a.fn1(Fn1::Floor, q);
            let m = a.mul(fl, dy);
            a.sub(dx, m)
        }
        D::Rem => {
            let q = a.fn2(Fn2::Div, x, y);
            let m = a.mul(q, dy);
            a.sub(dx, m)
        }
        D::Zero => a.zero(),
        rule => unreachable!("`{}` has the rule {rule:?} of another arity", f.name()),
    }
}

/// The partial derivative d e / d v.
pub fn partial(arena: &mut ExprArena, e: ExprId, v: ScalarId) -> ExprId {
    let mut var = |a: &mut ExprArena, s: ScalarId| if s == v { Some(a.one()) } else { None };
    let mut seed = Seed {
        var: &mut var,
        time: 0.0,
    };
    derivative(arena, e, &mut seed, &mut HashMap::default())
}

/// When `residual` (meaning `residual = 0`) is linear in `v` with a coefficient that
/// does not depend on `v`: the expression `v = -rest / coefficient` and the
/// coefficient. `None` when `v` enters nonlinearly (or under a relation or `if`
/// condition).
pub fn solve_linear(
    arena: &mut ExprArena,
    residual: ExprId,
    v: ScalarId,
) -> Option<(ExprId, ExprId)> {
    let coefficient = partial(arena, residual, v);
    if arena.as_const(coefficient) == Some(0.0) || arena.vars(coefficient).contains(&v) {
        return None;
    }
    if condition_mentions(arena, residual, v) {
        return None;
    }
    let zero = arena.zero();
    let rest = arena.substitute(
        residual,
        &|s| if s == v { Some(zero) } else { None },
        &mut HashMap::default(),
    );
    let neg = arena.neg(rest);
    let solution = arena.div(neg, coefficient);
    Some((solution, coefficient))
}

/// Whether `v` occurs in a relation or an `if` condition inside `e` (then `e` is not
/// linear in `v` even where its derivative looks constant).
fn condition_mentions(arena: &ExprArena, e: ExprId, v: ScalarId) -> bool {
    let mut stack = vec![e];
    let mut seen = rustc_hash::FxHashSet::default();
    while let Some(x) = stack.pop() {
        if !seen.insert(x) {
            continue;
        }
        match arena.node(x) {
            Node::Rel(..) | Node::Sample(..) => {
                if arena.vars(x).contains(&v) {
                    return true;
                }
            }
            Node::If(c, p, q) => {
                if arena.vars(c).contains(&v) {
                    return true;
                }
                stack.push(p);
                stack.push(q);
            }
            Node::Fn1(f, y) if f.is_discontinuous() => {
                if arena.vars(y).contains(&v) {
                    return true;
                }
            }
            _ => stack.extend(arena.children(x)),
        }
    }
    false
}
