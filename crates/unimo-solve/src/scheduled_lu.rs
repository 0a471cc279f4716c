//! A sparse LU for the small iteration matrices `shift * M - J` whose Jacobian pattern is
//! known: the pivot order (Markowitz on the pattern plus the diagonal, diagonal pivots) and
//! the fill are found once, and the elimination is compiled into a flat schedule of
//! multiply-adds on the positions of the filled pattern. Factoring runs that schedule, with
//! no search and no index arithmetic; solving walks the factors' rows. A pivot smaller than
//! [`PIVOT_TOLERANCE`] times the largest entry below it in its column (or zero, or not
//! finite) refuses the factorization, and the caller factors that matrix with partial
//! pivoting instead (`linear.rs`).
//!
//! POLLU (20 unknowns, 86 entries with the diagonal): 106 multiply-adds a factorization and
//! 94 stored entries in this order, against 2,660 and 400 for the dense LU.

use crate::linear::{LuScalar, ShiftedMatrix};
use crate::sparse_lu::{PivotRefused, PIVOT_TOLERANCE};
use crate::system::SparsityPattern;
use faer::c64;
use std::sync::{Arc, Mutex};

/// The analysis: the pivot order, the filled pattern's positions and the elimination's
/// schedule. It does not depend on the scalars, so a real and a complex LU of one pattern
/// (Radau5's) share it. Indices are `u32` (the schedule is only built for matrices far
/// smaller than that).
#[derive(Debug)]
pub(crate) struct Schedule {
    /// `old_of_new[k]`: the unknown eliminated at step `k`.
    old_of_new: Vec<u32>,
    /// The Jacobian's entries `(row, column)` and their position in the values, in the
    /// pattern's column-major order.
    entries: Vec<(u32, u32, u32)>,
    /// Position of each unknown's diagonal entry (original index).
    diagonal: Vec<u32>,
    /// Position of each step's pivot.
    pivots: Vec<u32>,
    /// Step `k`'s entries below its pivot (their positions) are
    /// `lower_positions[lower_starts[k]..lower_starts[k + 1]]`; likewise right of it.
    lower_starts: Vec<u32>,
    lower_positions: Vec<u32>,
    upper_starts: Vec<u32>,
    upper_positions: Vec<u32>,
    /// The forward substitution in one list: `(row, position, column)` of `L`'s entries,
    /// by column (`y[row] -= L[row, column] y[column]`).
    forward: Vec<(u32, u32, u32)>,
    /// The back substitution's `(position, column)` of `U`'s entries right of the
    /// diagonal, row `k`'s at `upper_starts[k]..upper_starts[k + 1]`.
    backward: Vec<(u32, u32)>,
    /// The updates' targets: for each step, for each entry below the pivot, for each
    /// entry right of it, the position of their product's target.
    targets: Vec<u32>,
    /// Entries of the filled pattern.
    stored: usize,
    pub work: Work,
}

/// The numeric factors of one matrix on a [`Schedule`] (every refactorization).
#[derive(Debug, Clone)]
pub(crate) struct ScheduledLu<T: LuScalar> {
    schedule: Arc<Schedule>,
    /// The filled pattern's values: `L` (unit lower, without its diagonal) and `U`.
    values: Vec<T>,
    inverse_pivots: Vec<T>,
    scratch: Vec<T>,
}

/// Multiply-adds of an analysis: factoring, and one solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Work {
    pub factor: usize,
    pub solve: usize,
}

impl Work {
    /// The dense LU's work on `size` unknowns.
    pub fn dense(size: usize) -> Work {
        let factor = (0..size).map(|k| (size - k - 1) * (size - k)).sum();
        Work {
            factor,
            solve: size * size,
        }
    }
}

/// The pivot order: at each step the remaining unknown whose diagonal pivot creates the
/// least fill bound `(r - 1)(c - 1)` (`r`, `c`: its row's and column's entries in the
/// remaining submatrix), the smaller `r + c` and then the lower index on ties. Returns the
/// order and the filled pattern (dense, row-major, original indices).
fn markowitz_order(pattern: &SparsityPattern) -> (Vec<usize>, Vec<bool>) {
    let n = pattern.size();
    let mut filled = vec![false; n * n];
    for j in 0..n {
        for &i in pattern.column(j) {
            filled[i * n + j] = true;
        }
        filled[j * n + j] = true;
    }
    let mut rows = vec![0usize; n];
    let mut columns = vec![0usize; n];
    for i in 0..n {
        for j in 0..n {
            if filled[i * n + j] {
                rows[i] += 1;
                columns[j] += 1;
            }
        }
    }
    let mut active = vec![true; n];
    let mut order = Vec::with_capacity(n);
    let (mut lower, mut upper) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for _ in 0..n {
        // The fill bound, then r + c, then the index, in one integer (each below 2^21).
        let key = |k: usize| {
            let (r, c) = (rows[k] as u64, columns[k] as u64);
            ((r - 1) * (c - 1)) << 42 | (r + c) << 21 | k as u64
        };
        let Some(k) = (0..n).filter(|&k| active[k]).min_by_key(|&k| key(k)) else {
            break;
        };
        active[k] = false;
        order.push(k);
        lower.clear();
        upper.clear();
        lower.extend((0..n).filter(|&i| active[i] && filled[i * n + k]));
        upper.extend((0..n).filter(|&j| active[j] && filled[k * n + j]));
        for &i in &lower {
            rows[i] -= 1;
            for &j in &upper {
                if !filled[i * n + j] {
                    filled[i * n + j] = true;
                    rows[i] += 1;
                    columns[j] += 1;
                }
            }
        }
        for &j in &upper {
            columns[j] -= 1;
        }
    }
    (order, filled)
}

/// How many patterns' analyses [`Schedule::shared`] keeps.
const SHARED_SCHEDULES: usize = 8;

/// The analyses of the patterns seen last, the most recent at the end. A sweep, a
/// benchmark or an FMU simulates one model many times, and its pattern is analysed once.
static SCHEDULES: Mutex<Vec<(SparsityPattern, Arc<Schedule>)>> = Mutex::new(Vec::new());

impl Schedule {
    /// The analysis of `pattern`: that of an equal pattern analysed before in this process
    /// (one of the last [`SHARED_SCHEDULES`]), else a new one, kept for the next run.
    /// The analysis depends on the pattern only, not on values or tolerances.
    pub fn shared(pattern: &SparsityPattern) -> Arc<Schedule> {
        let lock = || {
            SCHEDULES
                .lock()
                .unwrap_or_else(|poisoned| poisoned.into_inner())
        };
        {
            let mut schedules = lock();
            if let Some(at) = schedules.iter().position(|(seen, _)| seen == pattern) {
                let entry = schedules.remove(at);
                let schedule = entry.1.clone();
                schedules.push(entry);
                return schedule;
            }
        }
        let schedule = Arc::new(Schedule::analyze(pattern));
        let mut schedules = lock();
        if schedules.len() >= SHARED_SCHEDULES {
            schedules.remove(0);
        }
        schedules.push((pattern.clone(), schedule.clone()));
        schedule
    }

    /// Step `k`'s positions below its pivot and right of it.
    #[inline(always)]
    fn step(&self, k: usize) -> (&[u32], &[u32]) {
        let lower = self.lower_starts[k] as usize..self.lower_starts[k + 1] as usize;
        let upper = self.upper_starts[k] as usize..self.upper_starts[k + 1] as usize;
        (&self.lower_positions[lower], &self.upper_positions[upper])
    }

    /// Analyses the Jacobian pattern `pattern` (the diagonal is added).
    pub fn analyze(pattern: &SparsityPattern) -> Schedule {
        let n = pattern.size();
        let (order, filled) = markowitz_order(pattern);
        let mut new_of_old = vec![0usize; n];
        for (k, &old) in order.iter().enumerate() {
            new_of_old[old] = k;
        }
        // Positions of the filled pattern, row-major in the new order.
        let mut position = vec![u32::MAX; n * n];
        let mut stored = 0u32;
        for &old_row in &order {
            for &old_column in &order {
                if filled[old_row * n + old_column] {
                    position[new_of_old[old_row] * n + new_of_old[old_column]] = stored;
                    stored += 1;
                }
            }
        }
        let at = |row: usize, column: usize| position[new_of_old[row] * n + new_of_old[column]];
        let entries = (0..n)
            .flat_map(|j| pattern.column(j).iter().map(move |&i| (i, j)))
            .map(|(i, j)| (i as u32, j as u32, at(i, j)))
            .collect();
        let diagonal = (0..n).map(|i| at(i, i)).collect();
        let mut schedule = Schedule {
            old_of_new: order.iter().map(|&k| k as u32).collect(),
            entries,
            diagonal,
            pivots: Vec::with_capacity(n),
            lower_starts: vec![0],
            lower_positions: Vec::new(),
            upper_starts: vec![0],
            upper_positions: Vec::new(),
            targets: Vec::new(),
            forward: Vec::new(),
            backward: Vec::new(),
            stored: stored as usize,
            work: Work {
                factor: 0,
                solve: stored as usize,
            },
        };
        let (mut lower, mut upper) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for k in 0..n {
            schedule.pivots.push(position[k * n + k]);
            lower.clear();
            upper.clear();
            lower.extend((k + 1..n).filter(|&r| position[r * n + k] != u32::MAX));
            upper.extend((k + 1..n).filter(|&c| position[k * n + c] != u32::MAX));
            for &r in &lower {
                schedule.lower_positions.push(position[r * n + k]);
                schedule
                    .forward
                    .push((r as u32, position[r * n + k], k as u32));
                schedule
                    .targets
                    .extend(upper.iter().map(|&c| position[r * n + c]));
            }
            for &c in &upper {
                schedule.upper_positions.push(position[k * n + c]);
                schedule.backward.push((position[k * n + c], c as u32));
            }
            schedule
                .lower_starts
                .push(schedule.lower_positions.len() as u32);
            schedule
                .upper_starts
                .push(schedule.upper_positions.len() as u32);
            schedule.work.factor += lower.len() * (upper.len() + 1);
        }
        schedule
    }
}

impl<T: LuScalar> ScheduledLu<T> {
    /// Storage for the factors of matrices on `schedule`.
    pub fn new(schedule: Arc<Schedule>) -> Self {
        let n = schedule.pivots.len();
        ScheduledLu {
            values: vec![T::from(0.0); schedule.stored],
            inverse_pivots: vec![T::from(1.0); n],
            scratch: vec![T::from(0.0); n],
            schedule,
        }
    }

    /// The schedule, to share with a LU of other scalars.
    pub fn schedule(&self) -> &Arc<Schedule> {
        &self.schedule
    }

    /// Writes `matrix` (its Jacobian's entries on the analysed pattern) into the factors'
    /// storage and factors it.
    pub fn factor_shifted(&mut self, matrix: ShiftedMatrix<'_, T>) -> Result<(), PivotRefused> {
        let schedule = &*self.schedule;
        self.values.fill(T::from(0.0));
        for &(i, j, p) in &schedule.entries {
            let value = matrix.jacobian.get(i as usize, j as usize);
            self.values[p as usize] = T::from(0.0) - T::from(value);
        }
        let (values, diagonal) = (&mut self.values, &schedule.diagonal);
        matrix.for_each_shift(|i, shift| values[diagonal[i] as usize] += shift);
        self.factor()
    }

    fn factor(&mut self) -> Result<(), PivotRefused> {
        let schedule = &*self.schedule;
        let values = &mut self.values;
        let mut targets = schedule.targets.iter();
        for k in 0..schedule.pivots.len() {
            let (lower, upper) = schedule.step(k);
            let inverse = usable_inverse(values, schedule.pivots[k] as usize, lower)?;
            self.inverse_pivots[k] = inverse;
            for &p in lower {
                let l = values[p as usize] * inverse;
                values[p as usize] = l;
                for (&q, &target) in upper.iter().zip(targets.by_ref()) {
                    let u = values[q as usize];
                    values[target as usize] -= l * u;
                }
            }
        }
        Ok(())
    }

    /// Solves `A x = b` in place with the last factorization.
    pub fn solve(&mut self, b: &mut [T]) {
        let schedule = &*self.schedule;
        let y = &mut self.scratch;
        for (k, &old) in schedule.old_of_new.iter().enumerate() {
            y[k] = b[old as usize];
        }
        let values = &self.values;
        // L y = b (unit diagonal), column by column.
        for &(r, p, k) in &schedule.forward {
            let yk = y[k as usize];
            y[r as usize] -= values[p as usize] * yk;
        }
        // U x = y, from the last row up.
        for k in (0..y.len()).rev() {
            let range = schedule.upper_starts[k] as usize..schedule.upper_starts[k + 1] as usize;
            let mut s = y[k];
            for &(q, c) in &schedule.backward[range] {
                s -= values[q as usize] * y[c as usize];
            }
            y[k] = s * self.inverse_pivots[k];
        }
        for (k, &old) in schedule.old_of_new.iter().enumerate() {
            b[old as usize] = y[k];
        }
    }
}

/// Radau5's pair: a real and a complex matrix on one schedule, factored and solved in one
/// walk of it. Each scalar gets exactly the operations, in the order, of
/// [`ScheduledLu::factor`] and [`ScheduledLu::solve`] (the results are bit for bit those of
/// the two walks); the walk reads each index once for both, and the two matrices'
/// dependency chains overlap.
pub(crate) struct Pair<'a> {
    pub real: &'a mut ScheduledLu<f64>,
    pub complex: &'a mut ScheduledLu<c64>,
}

impl Pair<'_> {
    /// Whether both are on one schedule (else the caller walks each on its own).
    pub fn shares_schedule(&self) -> bool {
        Arc::ptr_eq(&self.real.schedule, &self.complex.schedule)
    }

    /// Writes both matrices and factors them; on a refusal of either, neither factorization
    /// is usable and the caller factors each on its own.
    pub fn factor_shifted(
        &mut self,
        real: ShiftedMatrix<'_, f64>,
        complex: ShiftedMatrix<'_, c64>,
    ) -> Result<(), PivotRefused> {
        debug_assert!(self.shares_schedule());
        let schedule = &*self.real.schedule;
        let (re, cx) = (&mut self.real.values, &mut self.complex.values);
        re.fill(0.0);
        cx.fill(c64::new(0.0, 0.0));
        for &(i, j, p) in &schedule.entries {
            let value = real.jacobian.get(i as usize, j as usize);
            re[p as usize] = 0.0 - value;
            let value = complex.jacobian.get(i as usize, j as usize);
            cx[p as usize] = c64::from(0.0) - c64::from(value);
        }
        let diagonal = &schedule.diagonal;
        real.for_each_shift(|i, shift| re[diagonal[i] as usize] += shift);
        complex.for_each_shift(|i, shift| cx[diagonal[i] as usize] += shift);
        self.factor()
    }

    fn factor(&mut self) -> Result<(), PivotRefused> {
        let schedule = &*self.real.schedule;
        let (re, cx) = (&mut self.real.values, &mut self.complex.values);
        let mut targets = schedule.targets.iter();
        for k in 0..schedule.pivots.len() {
            let (lower, upper) = schedule.step(k);
            let at = schedule.pivots[k] as usize;
            let inverse_re = usable_inverse(re, at, lower)?;
            let inverse_cx = usable_inverse(cx, at, lower)?;
            self.real.inverse_pivots[k] = inverse_re;
            self.complex.inverse_pivots[k] = inverse_cx;
            for &p in lower {
                let p = p as usize;
                let l_re = re[p] * inverse_re;
                let l_cx = cx[p] * inverse_cx;
                re[p] = l_re;
                cx[p] = l_cx;
                for (&q, &target) in upper.iter().zip(targets.by_ref()) {
                    let (q, target) = (q as usize, target as usize);
                    let (u_re, u_cx) = (re[q], cx[q]);
                    re[target] -= l_re * u_re;
                    cx[target] -= l_cx * u_cx;
                }
            }
        }
        Ok(())
    }

    /// Solves `A_re x = b` and `A_cx y = c` in place with the last factorizations.
    pub fn solve(&mut self, b: &mut [f64], c: &mut [c64]) {
        debug_assert!(self.shares_schedule());
        let schedule = &*self.real.schedule;
        let (y, z) = (&mut self.real.scratch, &mut self.complex.scratch);
        for (k, &old) in schedule.old_of_new.iter().enumerate() {
            y[k] = b[old as usize];
            z[k] = c[old as usize];
        }
        let (re, cx) = (&self.real.values, &self.complex.values);
        for &(r, p, k) in &schedule.forward {
            let (r, p, k) = (r as usize, p as usize, k as usize);
            let (yk, zk) = (y[k], z[k]);
            y[r] -= re[p] * yk;
            z[r] -= cx[p] * zk;
        }
        for k in (0..y.len()).rev() {
            let range = schedule.upper_starts[k] as usize..schedule.upper_starts[k + 1] as usize;
            let (mut s, mut t) = (y[k], z[k]);
            for &(q, col) in &schedule.backward[range] {
                let (q, col) = (q as usize, col as usize);
                s -= re[q] * y[col];
                t -= cx[q] * z[col];
            }
            y[k] = s * self.real.inverse_pivots[k];
            z[k] = t * self.complex.inverse_pivots[k];
        }
        for (k, &old) in schedule.old_of_new.iter().enumerate() {
            b[old as usize] = y[k];
            c[old as usize] = z[k];
        }
    }
}

/// The inverse of step `k`'s pivot at `values[at]`, if the pivot is usable (the test of
/// [`ScheduledLu::factor`]).
#[inline(always)]
fn usable_inverse<T: LuScalar>(values: &[T], at: usize, lower: &[u32]) -> Result<T, PivotRefused> {
    let pivot = values[at];
    let largest = lower
        .iter()
        .map(|&p| values[p as usize].pivot_size())
        .fold(0.0, f64::max);
    let inverse = T::from(1.0) / pivot;
    if !pivot.is_usable_pivot()
        || !inverse.is_usable_pivot()
        || pivot.pivot_size() < PIVOT_TOLERANCE * largest
    {
        return Err(PivotRefused);
    }
    Ok(inverse)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::small_lu::SmallLu;
    use crate::system::JacobianMatrix;

    fn shifted<'a, T>(
        jacobian: &'a JacobianMatrix,
        differential: &'a [bool],
        shift: T,
    ) -> ShiftedMatrix<'a, T> {
        ShiftedMatrix {
            jacobian,
            differential,
            shift,
        }
    }

    fn analyze<T: LuScalar>(pattern: &SparsityPattern) -> (ScheduledLu<T>, Work) {
        let schedule = Arc::new(Schedule::analyze(pattern));
        let work = schedule.work;
        (ScheduledLu::new(schedule), work)
    }

    /// The lower-triangular-plus-diagonal pattern of a chain, and one with an arrow (a
    /// dense first row and column: natural order fills everything, the right order none).
    fn arrow(n: usize) -> SparsityPattern {
        let entries = (0..n).flat_map(|i| [(0, i), (i, 0), (i, i)]);
        SparsityPattern::from_entries(n, entries).unwrap()
    }

    #[test]
    fn equal_patterns_share_one_analysis_and_other_patterns_do_not() {
        // Sizes no other test uses, so that tests running in parallel do not evict these.
        let (first, again) = (Schedule::shared(&arrow(37)), Schedule::shared(&arrow(37)));
        assert!(Arc::ptr_eq(&first, &again));
        let other = Schedule::shared(&arrow(38));
        assert!(!Arc::ptr_eq(&first, &other));
        assert_eq!(other.work, Schedule::analyze(&arrow(38)).work);
        // The cache is bounded: after enough other patterns the first is analysed anew.
        for n in 0..SHARED_SCHEDULES {
            Schedule::shared(&arrow(40 + n));
        }
        let evicted = Schedule::shared(&arrow(37));
        assert!(!Arc::ptr_eq(&first, &evicted));
        assert_eq!(evicted.work, first.work);
    }

    #[test]
    fn an_arrow_is_factored_without_fill() {
        let (lu, work) = analyze::<f64>(&arrow(10));
        // The hub goes in the last 2 x 2 block: each step before has one entry below and
        // one right of its pivot.
        assert!(!lu.schedule.old_of_new[..8].contains(&0));
        assert_eq!(lu.values.len(), 28);
        assert_eq!(
            work,
            Work {
                factor: 18,
                solve: 28
            }
        );
        assert_eq!(Work::dense(10).factor, 330);
    }

    fn jacobian_on(pattern: &SparsityPattern, seed: u64) -> JacobianMatrix {
        let mut s = seed;
        let mut jacobian = JacobianMatrix::dense(pattern.size());
        for j in 0..pattern.size() {
            for &i in pattern.column(j) {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let v = ((s >> 33) % 2001) as f64 / 100.0 - 10.0;
                assert!(jacobian.set(i, j, v));
            }
        }
        jacobian
    }

    /// Against the dense LU with partial pivoting, on real and complex shifts, where the
    /// shift keeps the diagonal pivots acceptable.
    #[test]
    fn agrees_with_the_dense_lu() {
        let pattern = SparsityPattern::from_entries(
            12,
            (0..12).flat_map(|i| [(i, (i * 5 + 3) % 12), ((i * 7) % 12, i), (i, (i + 1) % 12)]),
        )
        .unwrap();
        let jacobian = jacobian_on(&pattern, 17);
        let differential: Vec<bool> = (0..12).map(|i| i % 5 != 4).collect();
        let b: Vec<f64> = (0..12).map(|i| 1.0 - 0.3 * i as f64).collect();
        let (mut scheduled, _) = analyze::<f64>(&pattern);
        let mut dense = SmallLu::<f64>::new(12);
        scheduled
            .factor_shifted(shifted(&jacobian, &differential, 50.0))
            .unwrap();
        dense
            .factor_shifted(shifted(&jacobian, &differential, 50.0))
            .unwrap();
        let (mut x, mut y) = (b.clone(), b.clone());
        scheduled.solve(&mut x);
        dense.solve(&mut y);
        for i in 0..12 {
            assert!((x[i] - y[i]).abs() <= 1e-13 * (1.0 + y[i].abs()), "row {i}");
        }
        let shift = c64::new(40.0, -25.0);
        let (mut scheduled, _) = analyze::<c64>(&pattern);
        let mut dense = SmallLu::<c64>::new(12);
        scheduled
            .factor_shifted(shifted(&jacobian, &differential, shift))
            .unwrap();
        dense
            .factor_shifted(shifted(&jacobian, &differential, shift))
            .unwrap();
        let b: Vec<c64> = b.iter().map(|&v| c64::new(v, 2.0 * v)).collect();
        let (mut x, mut y) = (b.clone(), b.clone());
        scheduled.solve(&mut x);
        dense.solve(&mut y);
        for i in 0..12 {
            assert!(
                (x[i] - y[i]).norm() <= 1e-13 * (1.0 + y[i].norm()),
                "row {i}"
            );
        }
    }

    /// The pair's one walk gives the factors and solutions of the two walks, bit for bit,
    /// and refuses what either walk refuses.
    #[test]
    fn the_pair_walk_gives_the_bits_of_two_walks() {
        let n = 15;
        let pattern = SparsityPattern::from_entries(
            n,
            (0..n).flat_map(|i| [(i, (i * 4 + 1) % n), ((i * 6) % n, i), ((i + 2) % n, i)]),
        )
        .unwrap();
        let jacobian = jacobian_on(&pattern, 5);
        let differential = vec![true; n];
        let (re_shift, cx_shift) = (60.0, c64::new(45.0, -30.0));
        let (mut real, _) = analyze::<f64>(&pattern);
        let mut complex = ScheduledLu::<c64>::new(real.schedule.clone());
        let (mut paired_real, mut paired_complex) = (real.clone(), complex.clone());
        real.factor_shifted(shifted(&jacobian, &differential, re_shift))
            .unwrap();
        complex
            .factor_shifted(shifted(&jacobian, &differential, cx_shift))
            .unwrap();
        let mut pair = Pair {
            real: &mut paired_real,
            complex: &mut paired_complex,
        };
        assert!(pair.shares_schedule());
        pair.factor_shifted(
            shifted(&jacobian, &differential, re_shift),
            shifted(&jacobian, &differential, cx_shift),
        )
        .unwrap();
        let b: Vec<f64> = (0..n).map(|i| 0.7 - 0.2 * i as f64).collect();
        let c: Vec<c64> = b.iter().map(|&v| c64::new(v, 1.0 - v)).collect();
        let (mut x, mut y, mut px, mut py) = (b.clone(), c.clone(), b, c);
        real.solve(&mut x);
        complex.solve(&mut y);
        pair.solve(&mut px, &mut py);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let complex_bits = |v: &[c64]| v.iter().flat_map(|z| [z.re, z.im]).collect::<Vec<_>>();
        assert_eq!(bits(&x), bits(&px));
        assert_eq!(bits(&complex_bits(&y)), bits(&complex_bits(&py)));
        assert_eq!(bits(&real.values), bits(&paired_real.values));
        assert_eq!(
            bits(&complex_bits(&complex.values)),
            bits(&complex_bits(&paired_complex.values))
        );
        // A shift that leaves a zero pivot in the real matrix only: the pair refuses.
        let mut singular = JacobianMatrix::dense(2);
        for (i, j, v) in [(0, 0, 1.0), (1, 0, -1.0), (0, 1, -1.0), (1, 1, 3.0)] {
            assert!(singular.set(i, j, v));
        }
        let two = SparsityPattern::dense(2);
        let (mut real, _) = analyze::<f64>(&two);
        let mut complex = ScheduledLu::<c64>::new(real.schedule.clone());
        let mut pair = Pair {
            real: &mut real,
            complex: &mut complex,
        };
        let refused = pair.factor_shifted(
            shifted(&singular, &[true, true], 1.0),
            shifted(&singular, &[true, true], c64::new(1.0, 1.0)),
        );
        assert_eq!(refused, Err(PivotRefused));
    }

    /// A zero diagonal pivot, and one far below the entries of its column, are refused.
    #[test]
    fn small_pivots_are_refused() {
        let pattern = SparsityPattern::from_entries(2, [(0, 0), (1, 0), (0, 1), (1, 1)]).unwrap();
        let mut jacobian = JacobianMatrix::dense(2);
        for (i, j, v) in [(0, 0, 0.0), (1, 0, -1.0), (0, 1, -1.0), (1, 1, 0.0)] {
            assert!(jacobian.set(i, j, v));
        }
        let (mut lu, _) = analyze::<f64>(&pattern);
        assert_eq!(
            lu.factor_shifted(shifted(&jacobian, &[false, false], 1.0)),
            Err(PivotRefused)
        );
        assert!(jacobian.set(0, 0, -1e-6));
        assert_eq!(
            lu.factor_shifted(shifted(&jacobian, &[false, false], 1.0)),
            Err(PivotRefused)
        );
        assert!(jacobian.set(0, 0, -0.5));
        assert_eq!(
            lu.factor_shifted(shifted(&jacobian, &[false, false], 1.0)),
            Ok(())
        );
        let mut x = [1.0, 1.0];
        lu.solve(&mut x);
        // [[0.5, 1], [1, 0]] x = [1, 1]: x = [1, 0.5].
        assert!((x[0] - 1.0).abs() < 1e-15 && (x[1] - 0.5).abs() < 1e-15);
    }
}
