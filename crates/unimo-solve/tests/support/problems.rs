//! Test problems shared by the tests, the benchmark and the work-precision example: ROBER
//! (as a DAE), HIRES, VDPOL, POLLU from the Bari/CWI test set, plus small problems with known
//! solutions.
#![allow(dead_code, clippy::excessive_precision)]

#[path = "test_set.rs"]
mod test_set;

use unimo_solve::{
    EvalError, JacobianMatrix, Method, Options, SolveError, Solver, Stats, StopReason, System,
};

/// `impl System` for a test problem: its `rows` (true for a differential one, as many as
/// unknowns), its right-hand side as a block writing `f` from `y` (and `self`), its
/// Jacobian (optional) as a block setting the entries of `jac` at `y` and returning
/// whether it did, then the problem's other methods (roots) as in the impl. A
/// second-order equation `x'' = a(x, v)` gives instead of `rows` and `rhs` its
/// acceleration `a` from `x` and `v = x'` (and `self`): the system `(x, v)' = (v, a)`.
macro_rules! system {
    (
        $ty:ty,
        second_order: |$s:ident, $x:ident, $v:ident| $acceleration:expr,
        $($method:tt)*
    ) => {
        system! {
            $ty,
            rows: [true, true],
            rhs: |$s, y, f| {
                let ($x, $v) = (y[0], y[1]);
                f[0] = y[1];
                f[1] = $acceleration;
            }
            $($method)*
        }
    };
    (
        $ty:ty,
        rows: $rows:expr,
        rhs: |$s:ident, $y:ident, $f:ident| $rhs:block
        jacobian: |$js:ident, $jy:ident, $jac:ident| $jacobian:block
        $($method:tt)*
    ) => {
        system! {
            $ty,
            rows: $rows,
            rhs: |$s, $y, $f| $rhs
            fn jacobian(
                &mut $js,
                _t: f64,
                $jy: &[f64],
                $jac: &mut JacobianMatrix,
            ) -> Result<bool, EvalError> $jacobian
            $($method)*
        }
    };
    (
        $ty:ty,
        rows: $rows:expr,
        rhs: |$s:ident, $y:ident, $f:ident| $rhs:block
        $($method:tt)*
    ) => {
        impl System for $ty {
            fn len(&self) -> usize {
                $rows.len()
            }
            fn differential(&self) -> &[bool] {
                &$rows
            }
            fn rhs(&mut $s, _t: f64, $y: &[f64], $f: &mut [f64]) -> Result<(), EvalError> {
                $rhs
                Ok(())
            }
            $($method)*
        }
    };
}

/// A reference problem: system, initial point, end time, reference solution at the end.
pub struct Reference {
    pub name: &'static str,
    pub t_end: f64,
    pub x0: Vec<f64>,
    pub solution: Vec<f64>,
}

/// `-log10(max_i |x_i - ref_i| / |ref_i|)`.
pub fn significant_digits(x: &[f64], reference: &[f64]) -> f64 {
    let worst = x
        .iter()
        .zip(reference)
        .map(|(v, r)| ((v - r) / r).abs())
        .fold(0.0, f64::max);
    -worst.max(1e-300).log10()
}

/// Integrates from 0 to `t_end` and returns the final state and the counters.
pub fn solve_to(
    method: Method,
    system: &mut dyn System,
    x0: &[f64],
    t_end: f64,
    options: Options,
) -> Result<(Vec<f64>, Stats), SolveError> {
    let mut solver = Solver::new(method, system, 0.0, x0, options)?;
    match solver.step_until(system, t_end)? {
        StopReason::ReachedStop => {}
        other => panic!("unexpected stop {other:?}"),
    }
    assert_eq!(solver.current_time(), t_end);
    Ok((solver.state().to_vec(), solver.stats()))
}

/// The three stiff reference problems of the work-precision comparison.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Benchmark {
    Rober,
    Hires,
    VanDerPol,
}

impl Benchmark {
    pub const ALL: [Benchmark; 3] = [Benchmark::Rober, Benchmark::Hires, Benchmark::VanDerPol];

    pub fn reference(self) -> Reference {
        match self {
            Benchmark::Rober => Rober::reference(),
            Benchmark::Hires => Hires::reference(),
            Benchmark::VanDerPol => VanDerPol::reference(),
        }
    }

    pub fn system(self) -> Box<dyn System> {
        match self {
            Benchmark::Rober => Box::new(Rober {
                analytic_jacobian: true,
            }),
            Benchmark::Hires => Box::new(Hires),
            Benchmark::VanDerPol => Box::new(VanDerPol { epsilon: 1e-6 }),
        }
    }

    /// Absolute tolerance paired with `rtol` (ROBER 1e-6 rtol, HIRES 1e-4 rtol, VDPOL rtol).
    pub fn absolute_tolerance(self, rtol: f64) -> f64 {
        match self {
            Benchmark::Rober => rtol * 1e-6,
            Benchmark::Hires => rtol * 1e-4,
            Benchmark::VanDerPol => rtol,
        }
    }

    /// Solves once; returns scd and counters.
    pub fn run(self, method: Method, rtol: f64) -> Result<(f64, Stats), SolveError> {
        let reference = self.reference();
        let mut system = self.system();
        let options = Options::with_tolerances(rtol, self.absolute_tolerance(rtol));
        let (state, stats) = solve_to(
            method,
            system.as_mut(),
            &reference.x0,
            reference.t_end,
            options,
        )?;
        Ok((significant_digits(&state, &reference.solution), stats))
    }
}

/// Counters as a snapshot string.
pub fn counters(stats: &Stats) -> String {
    stats.to_text()
}

/// Robertson's chemical kinetics with the conservation law as algebraic row.
pub struct Rober {
    pub analytic_jacobian: bool,
}

impl Rober {
    pub fn reference() -> Reference {
        Reference {
            name: "ROBER",
            t_end: 1e11,
            x0: vec![1.0, 0.0, 0.0],
            solution: vec![
                2.083340149701255e-8,
                8.333360770334713e-14,
                0.9999999791665050,
            ],
        }
    }
}

system! {
    Rober,
    rows: [true, true, false],
    rhs: |self, y, out| {
        out[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
        out[1] = 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1];
        out[2] = y[0] + y[1] + y[2] - 1.0;
    }
    jacobian: |self, y, jac| {
        if !self.analytic_jacobian {
            return Ok(false);
        }
        jac.set(0, 0, -0.04);
        jac.set(0, 1, 1e4 * y[2]);
        jac.set(0, 2, 1e4 * y[1]);
        jac.set(1, 0, 0.04);
        jac.set(1, 1, -1e4 * y[2] - 6e7 * y[1]);
        jac.set(1, 2, -1e4 * y[1]);
        jac.set(2, 0, 1.0);
        jac.set(2, 1, 1.0);
        jac.set(2, 2, 1.0);
        Ok(true)
    }
}

/// HIRES: plant physiology, 8 stiff ODEs.
pub struct Hires;

impl Hires {
    pub fn reference() -> Reference {
        Reference {
            name: "HIRES",
            t_end: test_set::HIRES_T_END,
            x0: test_set::HIRES_X0.to_vec(),
            solution: test_set::HIRES_REF.to_vec(),
        }
    }
}

system! {
    Hires,
    rows: [true; 8],
    rhs: |self, y, f| {
        test_set::hires_rhs(y, f);
    }
    jacobian: |self, y, jac| {
        // One row of the Jacobian a line.
        #[rustfmt::skip]
        let entries = [
            (0, 0, -1.71), (0, 1, 0.43), (0, 2, 8.32),
            (1, 0, 1.71), (1, 1, -8.75),
            (2, 2, -10.03), (2, 3, 0.43), (2, 4, 0.035),
            (3, 1, 8.32), (3, 2, 1.71), (3, 3, -1.12),
            (4, 4, -1.745), (4, 5, 0.43), (4, 6, 0.43),
            (5, 3, 0.69), (5, 4, 1.71), (5, 5, -0.43 - 280.0 * y[7]), (5, 6, 0.69), (5, 7, -280.0 * y[5]),
            (6, 5, 280.0 * y[7]), (6, 6, -1.81), (6, 7, 280.0 * y[5]),
            (7, 5, -280.0 * y[7]), (7, 6, 1.81), (7, 7, -280.0 * y[5]),
        ];
        for (i, j, v) in entries {
            jac.set(i, j, v);
        }
        Ok(true)
    }
}

/// POLLU: air pollution, 20 stiff ODEs (Jacobian by finite differences).
pub struct Pollu;

impl Pollu {
    pub fn reference() -> Reference {
        Reference {
            name: "POLLU",
            t_end: test_set::POLLU_T_END,
            x0: test_set::POLLU_Y0.to_vec(),
            solution: test_set::POLLU_REF.to_vec(),
        }
    }
}

impl System for Pollu {
    fn len(&self) -> usize {
        20
    }
    fn differential(&self) -> &[bool] {
        &[true; 20]
    }
    fn rhs(&mut self, _t: f64, y: &[f64], f: &mut [f64]) -> Result<(), EvalError> {
        test_set::pollu_rhs(y, f);
        Ok(())
    }
}

/// Van der Pol in Lienard scaling: `y1' = y2`, `y2' = ((1 - y1^2) y2 - y1) / eps`.
pub struct VanDerPol {
    pub epsilon: f64,
}

impl VanDerPol {
    pub fn reference() -> Reference {
        Reference {
            name: "VDPOL",
            t_end: 2.0,
            x0: vec![2.0, 0.0],
            solution: vec![1.706167732170483, -0.8928097010247975],
        }
    }
}

system! {
    VanDerPol,
    second_order: |self, x, v| ((1.0 - x * x) * v - x) / self.epsilon,
    jacobian: |self, y, jac| {
        jac.set(0, 1, 1.0);
        jac.set(1, 0, (-2.0 * y[0] * y[1] - 1.0) / self.epsilon);
        jac.set(1, 1, (1.0 - y[0] * y[0]) / self.epsilon);
        Ok(true)
    }
}

/// Van der Pol unscaled: `y1' = y2`, `y2' = mu (1 - y1^2) y2 - y1` (finite-difference Jacobian).
pub struct VanDerPolUnscaled {
    pub mu: f64,
}

system! {
    VanDerPolUnscaled,
    second_order: |self, x, v| self.mu * (1.0 - x * x) * v - x,
}

/// `y' = lambda y`.
pub struct Dahlquist {
    pub lambda: f64,
}

system! {
    Dahlquist,
    rows: [true],
    rhs: |self, y, f| {
        f[0] = self.lambda * y[0];
    }
}

/// Kepler two-body problem `q'' = -q / |q|^3` as a first-order system (q1, q2, p1, p2).
pub struct Kepler;

impl Kepler {
    /// Initial state of an orbit with eccentricity `e` (period 2 pi).
    pub fn initial(eccentricity: f64) -> Vec<f64> {
        vec![
            1.0 - eccentricity,
            0.0,
            0.0,
            ((1.0 + eccentricity) / (1.0 - eccentricity)).sqrt(),
        ]
    }
}

system! {
    Kepler,
    rows: [true; 4],
    rhs: |self, y, f| {
        let r2 = y[0] * y[0] + y[1] * y[1];
        let r3 = r2 * r2.sqrt();
        f[0] = y[2];
        f[1] = y[3];
        f[2] = -y[0] / r3;
        f[3] = -y[1] / r3;
    }
}

/// Harmonic oscillator `x'' = -x`: `x = cos t`, `v = -sin t` from `(1, 0)`.
pub struct Harmonic;

system! {
    Harmonic,
    second_order: |self, x, _v| -x,
}

/// Falling ball `h'' = -g` with the root function `h`.
pub struct BouncingBall {
    pub gravity: f64,
}

system! {
    BouncingBall,
    second_order: |self, _h, _v| -self.gravity,
    fn n_roots(&self) -> usize {
        1
    }
    fn roots(&mut self, _t: f64, y: &[f64], g: &mut [f64]) -> Result<(), EvalError> {
        g[0] = y[0];
        Ok(())
    }
}
