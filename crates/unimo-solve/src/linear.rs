//! LU factorizations of the shifted iteration matrices `shift * M - J` of the implicit
//! methods (real shift for BDF and the real Radau block, complex shift for the complex Radau
//! block): below [`SMALL_DENSE_LIMIT`] unknowns our own row-major partial-pivoting LU
//! (`small_lu.rs`: faer's blocked kernels cost more in set-up than they save on an 18 x 18
//! matrix); above it faer's dense partial-pivoting LU factored in place in preallocated
//! storage; for small matrices with a known pattern the scheduled LU (`scheduled_lu.rs`,
//! chosen by [`iteration_lu`]); or a sparse LU (symbolic analysis once, numeric factorization on every
//! refactor) on the Jacobian's pattern plus the diagonal: our multifrontal LU with diagonal
//! pivots (`sparse_lu.rs`) while it accepts its pivots, faer's with partial pivoting after.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor as dense_factor, solve as dense_solve};
use faer::perm::PermRef;
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{c64, Conj, Mat, MatMut, Par};

use crate::options::LinearSolverChoice;
use crate::scheduled_lu::{Pair, Schedule, ScheduledLu, Work};
use crate::small_lu::SmallLu;
use crate::sparse_lu::{StaticLu, MIN_WORK_PER_ENTRY};
use crate::system::{JacobianMatrix, SparsityPattern, System};
use std::cell::Cell;
use std::sync::Arc;
use std::time::Instant;

thread_local! {
    /// Seconds this thread spent factoring and solving iteration matrices.
    static LINEAR_ALGEBRA_SECONDS: Cell<f64> = const { Cell::new(0.0) };
    /// Whether the hot path's fine timers run (see [`set_fine_timing`]).
    static FINE_TIMING: Cell<bool> = const { Cell::new(false) };
}

/// Turns the fine timers on or off for the calling thread: the time spent in LU
/// factorizations and solves here, and in the model's evaluations in the runtime. Off by
/// default: two clock readings per call cost as much as a small model's evaluation or a
/// 2 x 2 solve, so only runs that report the split (`unimo simulate --stats`) pay them.
pub fn set_fine_timing(on: bool) {
    FINE_TIMING.with(|c| c.set(on));
}

/// Whether the fine timers run on this thread.
#[inline]
pub fn fine_timing() -> bool {
    FINE_TIMING.with(Cell::get)
}

/// Seconds the calling thread has spent in LU factorizations and solves so far (all
/// solvers; take the difference of two readings for one stretch of work).
pub fn linear_algebra_seconds() -> f64 {
    LINEAR_ALGEBRA_SECONDS.with(Cell::get)
}

fn add_linear_algebra_time(started: Option<Instant>) {
    let Some(started) = started else {
        return;
    };
    let seconds = started.elapsed().as_secs_f64();
    LINEAR_ALGEBRA_SECONDS.with(|c| c.set(c.get() + seconds));
}

/// Dense iteration matrices with fewer unknowns than this are factored by [`SmallLu`].
pub const SMALL_DENSE_LIMIT: usize = 32;

/// Scalars the iteration matrices are built from: `f64` and `c64`.
pub(crate) trait LuScalar:
    faer::traits::ComplexField
    + Copy
    + From<f64>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
    + std::ops::AddAssign
    + std::ops::SubAssign
    + std::ops::MulAssign
{
    /// Nonzero and finite.
    fn is_usable_pivot(self) -> bool;

    /// The size compared to choose pivots: `|x|` for reals, `|re| + |im|` for complex
    /// numbers (LAPACK's choice for its complex LU).
    fn pivot_size(self) -> f64;
}

impl LuScalar for f64 {
    fn is_usable_pivot(self) -> bool {
        self != 0.0 && self.is_finite()
    }

    fn pivot_size(self) -> f64 {
        self.abs()
    }
}

impl LuScalar for c64 {
    fn is_usable_pivot(self) -> bool {
        (self.re != 0.0 || self.im != 0.0) && self.re.is_finite() && self.im.is_finite()
    }

    fn pivot_size(self) -> f64 {
        self.re.abs() + self.im.abs()
    }
}

/// Which LU factors a method's iteration matrices (`unimo simulate --stats`:
/// `linear_solver`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinearSolverKind {
    /// Dense LU with partial pivoting (our own below 32 unknowns, faer's above).
    Dense,
    /// The scheduled sparse LU of small matrices (`scheduled_lu.rs`); `refused` when it
    /// refused its diagonal pivots often enough that the dense LU took over.
    Scheduled { refused: bool },
    /// The sparse LU of large matrices (`sparse_lu.rs`, faer's after a refusal).
    Sparse,
}

impl LinearSolverKind {
    /// The name `--stats` prints.
    pub fn name(self) -> &'static str {
        match self {
            LinearSolverKind::Dense => "dense",
            LinearSolverKind::Scheduled { refused: false } => "scheduled",
            LinearSolverKind::Scheduled { refused: true } => "scheduled, then dense",
            LinearSolverKind::Sparse => "sparse",
        }
    }
}

/// The matrix `shift * M - J` a backend factors, `M_ii = 1` where `differential[i]`.
#[derive(Clone, Copy)]
pub(crate) struct ShiftedMatrix<'a, T> {
    pub jacobian: &'a JacobianMatrix,
    pub differential: &'a [bool],
    pub shift: T,
}

impl<T: LuScalar> ShiftedMatrix<'_, T> {
    /// Calls `add(i, j, value)` for `-J`'s stored entries, then `add(i, i, shift)` for the
    /// differential rows: added into zeroed storage, that is the matrix.
    pub fn for_each_term(&self, mut add: impl FnMut(usize, usize, T)) {
        self.jacobian
            .for_each_entry(|i, j, value| add(i, j, T::from(0.0) - T::from(value)));
        self.for_each_shift(|i, shift| add(i, i, shift));
    }

    /// Calls `add(i, shift)` for the differential rows.
    pub fn for_each_shift(&self, mut add: impl FnMut(usize, T)) {
        for (i, _) in self.differential.iter().enumerate().filter(|(_, d)| **d) {
            add(i, self.shift);
        }
    }
}

/// The factorization failed: a zero or non-finite pivot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct SingularMatrix;

/// Factors and solves `(shift * M - J) y = b` for a diagonal 0/1 mass matrix `M`.
pub(crate) struct ShiftedLu<T: LuScalar> {
    backend: Backend<T>,
}

enum Backend<T: LuScalar> {
    Small(SmallLu<T>),
    Scheduled(Box<ScheduledBackend<T>>),
    Dense(DenseBackend<T>),
    Sparse(Box<SparseBackend<T>>),
}

/// The scheduled sparse LU (`scheduled_lu.rs`), with a dense LU with partial pivoting for
/// the matrices whose diagonal pivots it refuses.
struct ScheduledBackend<T: LuScalar> {
    scheduled: ScheduledLu<T>,
    /// Created at the first refusal; after [`MAX_REFUSALS`] refusals it factors every matrix.
    fallback: Option<Box<ShiftedLu<T>>>,
    refusals: u32,
    /// Whether `fallback` holds the last factorization.
    on_fallback: bool,
}

/// Refusals of the scheduled LU's diagonal pivots after which the dense LU factors alone
/// (a refused attempt costs a part of a scheduled factorization, which is itself at most
/// [`SCHEDULED_WORK_FRACTION`] of a dense one).
const MAX_REFUSALS: u32 = 3;

/// The scheduled LU replaces the dense one when its factorization and one solve take at
/// most this fraction of the dense LU's multiply-adds (its indirect addressing costs more
/// per operation than the dense loops).
pub(crate) const SCHEDULED_WORK_FRACTION: f64 = 1.0 / 3.0;

/// Whether the implicit methods factor `system`'s iteration matrices with the sparse LU.
pub(crate) fn use_sparse(system: &dyn System, choice: LinearSolverChoice) -> bool {
    choice.picks_sparse(system.len(), system.sparsity().is_some())
}

/// The LU of `system`'s iteration matrices under `choice`: sparse where [`use_sparse`]
/// says so; otherwise, when the Jacobian's pattern is known and `choice` is `Auto`, the
/// scheduled sparse LU if its work is at most [`SCHEDULED_WORK_FRACTION`] of the dense
/// LU's; dense else.
pub(crate) fn iteration_lu<T: LuScalar>(
    system: &dyn System,
    choice: LinearSolverChoice,
) -> ShiftedLu<T> {
    let size = system.len();
    let Some(pattern) = system.sparsity() else {
        return ShiftedLu::dense(size);
    };
    if use_sparse(system, choice) {
        return ShiftedLu::sparse(pattern);
    }
    if choice == LinearSolverChoice::Auto {
        if let Some(scheduled) = ShiftedLu::scheduled(pattern, SCHEDULED_WORK_FRACTION) {
            return scheduled;
        }
    }
    ShiftedLu::dense(size)
}

/// faer's dense partial-pivoting LU, factored in place in preallocated storage.
struct DenseBackend<T: LuScalar> {
    factors: Mat<T>,
    permutation: Vec<usize>,
    permutation_inverse: Vec<usize>,
    /// Workspace of the factorization and the solves.
    buffer: MemBuffer,
}

struct SparseBackend<T: LuScalar> {
    /// The multifrontal LU with diagonal pivots (`sparse_lu.rs`), tried first; `None` when
    /// its analysis failed or it refused a pivot once (then faer's LU with partial pivoting
    /// factors every matrix).
    diagonal: Option<Box<StaticLu<T>>>,
    /// Whether `diagonal` was analysed yet, and whether it holds the last factorization.
    diagonal_analyzed: bool,
    diagonal_factored: bool,
    /// The least work per stored entry for which `diagonal` is used
    /// (`sparse_lu::MIN_WORK_PER_ENTRY`; 0 in tests of small matrices).
    diagonal_min_work: f64,
    pattern: SparsityPattern,
    diagonal_positions: Vec<usize>,
    /// Position in `pattern` of each stored entry of the Jacobian's own pattern.
    jacobian_positions: Option<Vec<usize>>,
    values: Vec<T>,
    symbolic: Option<SymbolicLu<usize>>,
    /// The factors, overwritten in place by every refactorization (no allocation once
    /// their storage has grown to size).
    numeric: NumericLu<usize, T>,
    /// Whether `numeric` holds the factors of the last matrix (false after a failure).
    factored: bool,
    /// Workspace of the numeric factorization and the solves, sized with the symbolic
    /// analysis.
    buffer: Option<MemBuffer>,
}

impl<T: LuScalar> ShiftedLu<T> {
    /// Dense LU of a `size × size` matrix (our own below [`SMALL_DENSE_LIMIT`], faer's
    /// above).
    pub fn dense(size: usize) -> Self {
        if size < SMALL_DENSE_LIMIT {
            return ShiftedLu {
                backend: Backend::Small(SmallLu::new(size)),
            };
        }
        Self::faer_dense(size)
    }

    /// The scheduled sparse LU on `jacobian_pattern` plus the diagonal, if its work is at
    /// most `fraction` of the dense LU's (`None` otherwise).
    pub fn scheduled(jacobian_pattern: &SparsityPattern, fraction: f64) -> Option<Self> {
        let size = jacobian_pattern.size();
        if size >= crate::options::SPARSE_AUTO_THRESHOLD.max(SMALL_DENSE_LIMIT) {
            return None;
        }
        let schedule = Schedule::shared(jacobian_pattern);
        let cost = |w: Work| (w.factor + w.solve) as f64;
        if cost(schedule.work) > fraction * cost(Work::dense(size)) {
            return None;
        }
        Some(Self::on_schedule(schedule))
    }

    fn on_schedule(schedule: Arc<Schedule>) -> Self {
        ShiftedLu {
            backend: Backend::Scheduled(Box::new(ScheduledBackend {
                scheduled: ScheduledLu::new(schedule),
                fallback: None,
                refusals: 0,
                on_fallback: false,
            })),
        }
    }

    /// A LU of the same kind for matrices of other scalars (Radau5's complex one beside
    /// its real one), sharing the scheduled LU's analysis.
    pub fn sibling<U: LuScalar>(&self) -> ShiftedLu<U> {
        match &self.backend {
            Backend::Small(small) => ShiftedLu::dense(small.size()),
            Backend::Scheduled(s) => ShiftedLu::on_schedule(s.scheduled.schedule().clone()),
            Backend::Dense(dense) => ShiftedLu::faer_dense(dense.factors.nrows()),
            Backend::Sparse(sparse) => ShiftedLu::sparse(&sparse.pattern),
        }
    }

    /// faer's dense LU of a `size × size` matrix, whatever its size.
    pub fn faer_dense(size: usize) -> Self {
        ShiftedLu {
            backend: Backend::Dense(DenseBackend::new(size)),
        }
    }

    /// Sparse LU on `jacobian_pattern` plus the diagonal.
    pub fn sparse(jacobian_pattern: &SparsityPattern) -> Self {
        let pattern = jacobian_pattern.with_diagonal();
        let size = pattern.size();
        let diagonal_positions = (0..size)
            .map(|i| pattern.position(i, i).unwrap_or(0))
            .collect();
        let values = vec![T::from(0.0); pattern.nonzeros()];
        ShiftedLu {
            backend: Backend::Sparse(Box::new(SparseBackend {
                diagonal: None,
                diagonal_analyzed: false,
                diagonal_factored: false,
                diagonal_min_work: MIN_WORK_PER_ENTRY,
                pattern,
                diagonal_positions,
                jacobian_positions: None,
                values,
                symbolic: None,
                numeric: NumericLu::new(),
                factored: false,
                buffer: None,
            })),
        }
    }

    /// The multifrontal LU tried whatever its work per entry (tests of small matrices).
    #[cfg(test)]
    pub(crate) fn always_try_diagonal(&mut self) {
        if let Backend::Sparse(sparse) = &mut self.backend {
            sparse.diagonal_min_work = 0.0;
        }
    }

    /// Factors `shift * M - J`, where `M_ii = 1` when `differential[i]`.
    pub fn factor(
        &mut self,
        jacobian: &JacobianMatrix,
        differential: &[bool],
        shift: T,
    ) -> Result<(), SingularMatrix> {
        let started = fine_timing().then(Instant::now);
        let factored = self.factor_untimed(ShiftedMatrix {
            jacobian,
            differential,
            shift,
        });
        add_linear_algebra_time(started);
        factored
    }

    fn factor_untimed(&mut self, matrix: ShiftedMatrix<'_, T>) -> Result<(), SingularMatrix> {
        match &mut self.backend {
            Backend::Small(small) => small.factor_shifted(matrix),
            Backend::Scheduled(scheduled) => scheduled.factor(matrix),
            Backend::Dense(dense) => dense.factor(matrix),
            Backend::Sparse(sparse) => sparse.factor(matrix),
        }
    }

    /// Which LU this is.
    pub fn kind(&self) -> LinearSolverKind {
        match &self.backend {
            Backend::Small(_) | Backend::Dense(_) => LinearSolverKind::Dense,
            Backend::Scheduled(s) => LinearSolverKind::Scheduled {
                refused: s.refusals >= MAX_REFUSALS,
            },
            Backend::Sparse(_) => LinearSolverKind::Sparse,
        }
    }

    /// Solves in place with the last factorization.
    pub fn solve(&mut self, rhs: &mut [T]) {
        let started = fine_timing().then(Instant::now);
        self.solve_untimed(rhs);
        add_linear_algebra_time(started);
    }

    fn solve_untimed(&mut self, rhs: &mut [T]) {
        match &mut self.backend {
            Backend::Small(small) => small.solve(rhs),
            Backend::Scheduled(scheduled) => scheduled.solve(rhs),
            Backend::Dense(dense) => dense.solve(rhs),
            Backend::Sparse(sparse) => sparse.solve(rhs),
        }
    }
}

/// Radau5's real and complex LU of one Jacobian: on one schedule they are factored and
/// solved in one walk ([`scheduled_lu::Pair`], the same bits as two walks); otherwise each
/// on its own.
pub(crate) struct LuPair {
    pub real: ShiftedLu<f64>,
    pub complex: ShiftedLu<c64>,
}

impl<T: LuScalar> ShiftedLu<T> {
    /// The scheduled LU holds the last factorization.
    fn scheduled_factored(&mut self) {
        if let Backend::Scheduled(s) = &mut self.backend {
            s.on_fallback = false;
        }
    }

    /// Whether the scheduled LU (not its fallback) holds the last factorization.
    fn scheduled_holds_factors(&self) -> bool {
        matches!(&self.backend, Backend::Scheduled(s) if !s.on_fallback)
    }
}

impl LuPair {
    /// The real LU for `system` under `choice` and its complex sibling.
    pub fn new(system: &dyn System, choice: LinearSolverChoice) -> Self {
        let real: ShiftedLu<f64> = iteration_lu(system, choice);
        let complex = real.sibling();
        LuPair { real, complex }
    }

    /// Both scheduled, neither on its fallback, on one schedule.
    fn scheduled(&mut self) -> Option<Pair<'_>> {
        match (&mut self.real.backend, &mut self.complex.backend) {
            (Backend::Scheduled(real), Backend::Scheduled(complex))
                if real.refusals < MAX_REFUSALS && complex.refusals < MAX_REFUSALS =>
            {
                let pair = Pair {
                    real: &mut real.scheduled,
                    complex: &mut complex.scheduled,
                };
                pair.shares_schedule().then_some(pair)
            }
            _ => None,
        }
    }

    /// Factors `shift_re M - J` and `shift_cx M - J`; false when either is singular (the
    /// complex one is not factored when the real one is).
    pub fn factor(
        &mut self,
        jacobian: &JacobianMatrix,
        differential: &[bool],
        (shift_re, shift_cx): (f64, c64),
    ) -> bool {
        let started = fine_timing().then(Instant::now);
        let real = ShiftedMatrix {
            jacobian,
            differential,
            shift: shift_re,
        };
        let complex = ShiftedMatrix {
            jacobian,
            differential,
            shift: shift_cx,
        };
        let fused = self
            .scheduled()
            .is_some_and(|mut pair| pair.factor_shifted(real, complex).is_ok());
        let factored = if fused {
            self.real.scheduled_factored();
            self.complex.scheduled_factored();
            true
        } else {
            self.real.factor_untimed(real).is_ok() && self.complex.factor_untimed(complex).is_ok()
        };
        add_linear_algebra_time(started);
        factored
    }

    /// Solves with both last factorizations: `b` with the real one, `c` with the complex.
    pub fn solve(&mut self, b: &mut [f64], c: &mut [c64]) {
        let started = fine_timing().then(Instant::now);
        let both = self.real.scheduled_holds_factors() && self.complex.scheduled_holds_factors();
        match self.scheduled().filter(|_| both) {
            Some(mut pair) => pair.solve(b, c),
            None => {
                self.real.solve_untimed(b);
                self.complex.solve_untimed(c);
            }
        }
        add_linear_algebra_time(started);
    }
}

impl<T: LuScalar> ScheduledBackend<T> {
    fn factor(&mut self, matrix: ShiftedMatrix<'_, T>) -> Result<(), SingularMatrix> {
        if self.refusals < MAX_REFUSALS {
            if self.scheduled.factor_shifted(matrix).is_ok() {
                self.on_fallback = false;
                return Ok(());
            }
            self.refusals += 1;
        }
        self.on_fallback = true;
        let size = matrix.jacobian.size();
        let fallback = self
            .fallback
            .get_or_insert_with(|| Box::new(ShiftedLu::dense(size)));
        fallback.factor_untimed(matrix)
    }

    fn solve(&mut self, rhs: &mut [T]) {
        match (&mut self.fallback, self.on_fallback) {
            (Some(fallback), true) => fallback.solve_untimed(rhs),
            _ => self.scheduled.solve(rhs),
        }
    }
}

impl<T: LuScalar> DenseBackend<T> {
    fn new(size: usize) -> Self {
        let factor_req =
            dense_factor::lu_in_place_scratch::<usize, T>(size, size, Par::Seq, Default::default());
        let solve_req = dense_solve::solve_in_place_scratch::<usize, T>(size, 1, Par::Seq);
        DenseBackend {
            factors: Mat::zeros(size, size),
            permutation: vec![0; size],
            permutation_inverse: vec![0; size],
            buffer: MemBuffer::new(factor_req.or(solve_req)),
        }
    }

    fn factor(&mut self, matrix: ShiftedMatrix<'_, T>) -> Result<(), SingularMatrix> {
        let factors = &mut self.factors;
        factors.fill(T::from(0.0));
        matrix.for_each_term(|i, j, value| factors[(i, j)] += value);
        dense_factor::lu_in_place(
            factors.as_mut(),
            &mut self.permutation,
            &mut self.permutation_inverse,
            Par::Seq,
            MemStack::new(&mut self.buffer),
            Default::default(),
        );
        let singular = (0..factors.nrows()).any(|i| !factors[(i, i)].is_usable_pivot());
        if singular {
            Err(SingularMatrix)
        } else {
            Ok(())
        }
    }

    fn solve(&mut self, rhs: &mut [T]) {
        let size = self.factors.nrows();
        let perm = PermRef::new_checked(&self.permutation, &self.permutation_inverse, size);
        dense_solve::solve_in_place_with_conj(
            self.factors.as_ref(),
            self.factors.as_ref(),
            perm,
            Conj::No,
            MatMut::from_column_major_slice_mut(rhs, size, 1),
            Par::Seq,
            MemStack::new(&mut self.buffer),
        );
    }
}

impl<T: LuScalar> SparseBackend<T> {
    fn factor(&mut self, matrix: ShiftedMatrix<'_, T>) -> Result<(), SingularMatrix> {
        self.values.fill(T::from(0.0));
        self.scatter_jacobian(matrix.jacobian);
        let (values, diagonal) = (&mut self.values, &self.diagonal_positions);
        matrix.for_each_shift(|i, shift| values[diagonal[i]] += shift);
        self.diagonal_factored = false;
        if !self.diagonal_analyzed {
            self.diagonal_analyzed = true;
            self.diagonal = StaticLu::analyze(&self.pattern, self.diagonal_min_work).map(Box::new);
        }
        if let Some(diagonal) = &mut self.diagonal {
            if diagonal.factor(&self.values).is_ok() {
                self.diagonal_factored = true;
                return Ok(());
            }
            self.diagonal = None;
        }
        self.factor_pivoting()
    }

    /// faer's sparse LU with partial pivoting of the assembled `values`.
    fn factor_pivoting(&mut self) -> Result<(), SingularMatrix> {
        let size = self.pattern.size();
        let symbolic_matrix = SymbolicSparseColMatRef::new_checked(
            size,
            size,
            self.pattern.column_starts(),
            None,
            self.pattern.row_indices(),
        );
        if self.symbolic.is_none() {
            let symbolic = factorize_symbolic_lu(symbolic_matrix, Default::default())
                .map_err(|_| SingularMatrix)?;
            let scratch = symbolic
                .factorize_numeric_lu_scratch::<T>(Par::Seq, Default::default())
                .or(symbolic.solve_in_place_scratch::<T>(1, Par::Seq));
            self.buffer = Some(MemBuffer::try_new(scratch).map_err(|_| SingularMatrix)?);
            self.symbolic = Some(symbolic);
        }
        let (Some(symbolic), Some(buffer)) = (&self.symbolic, &mut self.buffer) else {
            return Err(SingularMatrix);
        };
        let matrix = SparseColMatRef::new(symbolic_matrix, &self.values);
        self.factored = false;
        symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                matrix,
                Par::Seq,
                MemStack::new(buffer),
                Default::default(),
            )
            .map_err(|_| SingularMatrix)?;
        self.factored = true;
        Ok(())
    }

    fn solve(&mut self, rhs: &mut [T]) {
        if self.diagonal_factored {
            if let Some(diagonal) = &mut self.diagonal {
                return diagonal.solve(rhs);
            }
        }
        let rhs = MatMut::from_column_major_slice_mut(rhs, self.pattern.size(), 1);
        let (true, Some(symbolic), Some(buffer)) =
            (self.factored, &self.symbolic, &mut self.buffer)
        else {
            return;
        };
        LuRef::new_unchecked(symbolic, &self.numeric).solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(buffer),
        );
    }

    /// Writes `-J` into the values of `pattern`.
    fn scatter_jacobian(&mut self, jacobian: &JacobianMatrix) {
        if let Some(jacobian_pattern) = jacobian.pattern() {
            let positions = self.jacobian_positions.get_or_insert_with(|| {
                (0..jacobian_pattern.size())
                    .flat_map(|j| jacobian_pattern.column(j).iter().map(move |&i| (i, j)))
                    .map(|(i, j)| self.pattern.position(i, j).unwrap_or(0))
                    .collect()
            });
            let mut index = 0;
            let values = &mut self.values;
            jacobian.for_each_entry(|_, _, value| {
                values[positions[index]] += T::from(0.0) - T::from(value);
                index += 1;
            });
        } else {
            let pattern = &self.pattern;
            let values = &mut self.values;
            jacobian.for_each_entry(|i, j, value| {
                if let Some(position) = pattern.position(i, j) {
                    values[position] += T::from(0.0) - T::from(value);
                }
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn example_jacobian(sparse: bool) -> JacobianMatrix {
        let entries = [
            (0, 0, 2.0),
            (1, 0, 1.0),
            (0, 1, -1.0),
            (1, 1, 3.0),
            (2, 2, 0.5),
        ];
        let mut jacobian = if sparse {
            let pattern =
                SparsityPattern::from_entries(3, entries.iter().map(|(i, j, _)| (*i, *j))).unwrap();
            JacobianMatrix::sparse(pattern)
        } else {
            JacobianMatrix::dense(3)
        };
        for (i, j, v) in entries {
            assert!(jacobian.set(i, j, v));
        }
        jacobian
    }

    fn check_residual(sparse: bool) {
        let jacobian = example_jacobian(sparse);
        let differential = [true, true, false];
        let mut lu = if sparse {
            ShiftedLu::<f64>::sparse(jacobian.pattern().unwrap())
        } else {
            ShiftedLu::<f64>::dense(3)
        };
        lu.factor(&jacobian, &differential, 5.0).unwrap();
        let mut x = [1.0, 2.0, 3.0];
        lu.solve(&mut x);
        // (5 M - J) x = b with b = (1, 2, 3)
        let a = |i: usize, j: usize| {
            let m = if i == j && differential[i] { 5.0 } else { 0.0 };
            m - jacobian.get(i, j)
        };
        for (i, expected) in [1.0, 2.0, 3.0].iter().enumerate() {
            let value: f64 = (0..3).map(|j| a(i, j) * x[j]).sum();
            assert!((value - expected).abs() < 1e-14, "row {i}: {value}");
        }
    }

    #[test]
    fn dense_solves_shifted_system() {
        check_residual(false);
    }

    #[test]
    fn sparse_solves_shifted_system() {
        check_residual(true);
    }

    /// A zero diagonal that the elimination order meets first (the algebraic row 3, of the
    /// least degree: coupled to row 0 only): the diagonal LU refuses it and faer's pivoting LU solves.
    #[test]
    fn a_refused_diagonal_pivot_falls_back_to_partial_pivoting() {
        let entries = [
            (0, 0, 1.0),
            (1, 1, 2.0),
            (2, 2, 3.0),
            (1, 2, 1.0),
            (2, 1, 1.0),
            (0, 1, 0.5),
            (1, 0, 0.5),
            (0, 2, 0.5),
            (2, 0, 0.5),
        ];
        let entries = entries
            .into_iter()
            .chain([(3, 0, 1.0), (0, 3, 1.0), (3, 3, 0.0)]);
        let entries: Vec<_> = entries.collect();
        let pattern = SparsityPattern::from_entries(4, entries.iter().map(|e| (e.0, e.1))).unwrap();
        let mut jacobian = JacobianMatrix::sparse(pattern.clone());
        for &(i, j, v) in &entries {
            jacobian.set(i, j, v);
        }
        let differential = [true, true, true, false];
        let mut lu = ShiftedLu::<f64>::sparse(&pattern);
        lu.always_try_diagonal();
        lu.factor(&jacobian, &differential, 5.0).unwrap();
        let Backend::Sparse(sparse) = &lu.backend else {
            panic!("not sparse");
        };
        assert!(sparse.diagonal.is_none() && !sparse.diagonal_factored);
        let mut x = [1.0, 2.0, 3.0, 4.0];
        lu.solve(&mut x);
        for (i, expected) in [1.0, 2.0, 3.0, 4.0].iter().enumerate() {
            let m = |i: usize, j: usize| if i == j && differential[i] { 5.0 } else { 0.0 };
            let value: f64 = (0..4).map(|j| (m(i, j) - jacobian.get(i, j)) * x[j]).sum();
            assert!((value - expected).abs() < 1e-14, "row {i}: {value}");
        }
    }

    /// Radau5's pair: the one walk gives the bits of two apart, and a matrix whose diagonal
    /// pivot the schedule refuses (a zero one) is factored with partial pivoting.
    #[test]
    fn the_lu_pair_walks_once_and_falls_back_where_a_pivot_is_refused() {
        let pattern = SparsityPattern::dense(2);
        let mut jacobian = JacobianMatrix::dense(2);
        for (i, j, v) in [(0, 0, 0.0), (1, 0, 1.0), (0, 1, 1.0), (1, 1, 0.0)] {
            jacobian.set(i, j, v);
        }
        let shifts = (5.0, c64::new(4.0, 3.0));
        let (b, c) = ([1.0, 2.0], [c64::new(1.0, -1.0), c64::new(2.0, 0.5)]);
        for (differential, refused) in [([true; 2], false), ([false; 2], true)] {
            let real = ShiftedLu::<f64>::scheduled(&pattern, 1.0).expect("scheduled");
            let mut pair = LuPair {
                complex: real.sibling(),
                real,
            };
            assert!(pair.factor(&jacobian, &differential, shifts));
            assert_eq!(pair.real.scheduled_holds_factors(), !refused);
            assert_eq!(pair.complex.scheduled_holds_factors(), !refused);
            let (mut x, mut y) = (b, c);
            pair.solve(&mut x, &mut y);
            // (shift M - J) y = c, row by row.
            for i in 0..2 {
                let m = |j: usize| {
                    if i == j && differential[i] {
                        shifts.1
                    } else {
                        c64::new(0.0, 0.0)
                    }
                };
                let row: c64 = (0..2)
                    .map(|j| (m(j) - c64::from(jacobian.get(i, j))) * y[j])
                    .sum();
                assert!((row - c[i]).norm() < 1e-14, "row {i}");
            }
            // Apart, on fresh LUs: the same bits.
            let mut real = ShiftedLu::<f64>::scheduled(&pattern, 1.0).unwrap();
            let mut complex: ShiftedLu<c64> = real.sibling();
            real.factor(&jacobian, &differential, shifts.0).unwrap();
            complex.factor(&jacobian, &differential, shifts.1).unwrap();
            let (mut x_apart, mut y_apart) = (b, c);
            real.solve(&mut x_apart);
            complex.solve(&mut y_apart);
            assert_eq!(x.map(f64::to_bits), x_apart.map(f64::to_bits));
            assert_eq!(y.map(|z| z.re.to_bits()), y_apart.map(|z| z.re.to_bits()));
            assert_eq!(y.map(|z| z.im.to_bits()), y_apart.map(|z| z.im.to_bits()));
        }
    }

    #[test]
    fn complex_shift_solves() {
        let jacobian = example_jacobian(false);
        let mut lu = ShiftedLu::<c64>::dense(3);
        lu.factor(&jacobian, &[true, true, false], c64::new(1.0, 2.0))
            .unwrap();
        let mut x = [c64::new(1.0, 0.0), c64::new(0.0, 1.0), c64::new(1.0, 1.0)];
        lu.solve(&mut x);
        // third row: -0.5 x2 = 1 + i
        assert!((x[2] - c64::new(-2.0, -2.0)).norm() < 1e-14);
    }

    #[test]
    fn singular_matrix_is_reported() {
        let jacobian = JacobianMatrix::dense(2);
        let mut lu = ShiftedLu::<f64>::dense(2);
        assert_eq!(
            lu.factor(&jacobian, &[true, false], 1.0),
            Err(SingularMatrix)
        );
    }
}
