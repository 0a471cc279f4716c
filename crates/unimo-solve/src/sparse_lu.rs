//! Multifrontal sparse LU with diagonal pivots for iteration matrices `shift * M - J`: the
//! fill-reducing order is AMD on the symmetrized pattern `A + Aᵀ` (UMFPACK's symmetric
//! strategy, and KLU's default, for matrices whose pivots can stay on the diagonal), the
//! supernodes and their row patterns are faer's symbolic Cholesky of that pattern, and the
//! numeric factorization runs front by front with dense kernels and no pivot search. A
//! pivot smaller than [`PIVOT_TOLERANCE`] times the largest entry below it in its column
//! (or zero, or not finite) refuses the factorization: the caller then uses a LU with
//! partial pivoting (faer's, `linear.rs`).
//!
//! Storage per supernode `t` (columns `begin..end`, `k` of them; `r` rows below them,
//! `rows_t`): the front's first `k` columns (`m = k + r` rows, column-major) hold `L` (unit
//! lower, below the diagonal) and the diagonal block's `U`, whose diagonal is stored as the
//! pivots' inverses (the back substitution multiplies: a division's latency would chain
//! its steps); a `k × r` block the rest of the `k` rows of `U`; an `r × r` block collects
//! the Schur complements of the children and the front's own before they are added into
//! the parent's front.

use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SymbolicSparseColMatRef;
use faer::Side;

use crate::linear::LuScalar;
use crate::system::SparsityPattern;

/// A diagonal pivot is kept when it is at least this fraction of the largest entry below it
/// in its column (KLU's and UMFPACK's default tolerance for preferring the diagonal).
pub(crate) const PIVOT_TOLERANCE: f64 = 1e-3;

/// Fronts are factored by plain loops, which cost about twice faer's blocked kernels per
/// operation on a large dense front (a dense 400 x 400 matrix: 4.9 against 2.4 ms; at 200,
/// 0.62 against 0.45 ms; at 100, 0.09 against 0.48): a pattern whose analysis gives a
/// front wider than this is left to faer's LU.
const MAX_FRONT_WIDTH: usize = 256;

/// Below this many multiply-adds per stored entry of the fronts, the factors have little
/// fill and dense blocks do not pay: faer's LU is used, which makes the same choice
/// between its simplicial and its supernodal LU by the same ratio (40, its
/// `LU_SUPERNODAL_RATIO_FACTOR`). A chain of 50,000 unknowns: 15 per entry, our solve
/// 0.85 ms against faer's 0.39; BRUSS2D's pattern: 71 per entry, 0.100 against 0.131.
pub(crate) const MIN_WORK_PER_ENTRY: f64 = 40.0;

/// A front's place in the storage and in the tree.
#[derive(Debug, Clone)]
struct Front {
    begin: usize,
    end: usize,
    /// Its rows below the diagonal block, in `rows`.
    rows: std::ops::Range<usize>,
    /// Offsets of its `L` panel and of its `U` block in `factors`, of its Schur block in
    /// `schur`.
    lower: usize,
    upper: usize,
    schur: usize,
    /// The parent and, for each row below, its index in the parent's front.
    parent: Option<usize>,
    relative: Vec<usize>,
}

impl Front {
    fn width(&self) -> usize {
        self.end - self.begin
    }

    fn below(&self) -> usize {
        self.rows.len()
    }
}

/// The factorization refused a pivot (see the module's documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PivotRefused;

/// The symbolic analysis (once) and the numeric factors (every refactorization).
pub(crate) struct StaticLu<T: LuScalar> {
    /// `new_of_old[i]`: the position of unknown `i` in the elimination order.
    new_of_old: Vec<usize>,
    old_of_new: Vec<usize>,
    fronts: Vec<Front>,
    /// Rows below the diagonal blocks of all fronts (elimination order).
    rows: Vec<usize>,
    /// For each stored entry of the matrix's pattern: where it is added in `factors`.
    assembly: Vec<usize>,
    factors: Vec<T>,
    schur: Vec<T>,
    work: Vec<T>,
    /// Scratch of the solves: one front's rows below its diagonal block.
    below: Vec<T>,
    /// Whether this CPU runs the kernels compiled for AVX2 ([`has_avx2`]).
    avx2: bool,
}

impl<T: LuScalar> StaticLu<T> {
    /// The symbolic analysis of `pattern` (with its diagonal); `None` when faer's analysis
    /// fails or gives no supernodal structure, a front wider than [`MAX_FRONT_WIDTH`] or
    /// less work per stored entry than `min_work_per_entry` ([`MIN_WORK_PER_ENTRY`]; the
    /// tests of small matrices pass 0).
    pub(crate) fn analyze(pattern: &SparsityPattern, min_work_per_entry: f64) -> Option<Self> {
        let n = pattern.size();
        let (starts, indices) = symmetrized(pattern);
        let matrix = SymbolicSparseColMatRef::new_checked(n, n, &starts, None, &indices);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic =
            factorize_symbolic_cholesky(matrix, Side::Lower, SymmetricOrdering::Amd, params)
                .ok()?;
        let (old_of_new, new_of_old) = match symbolic.perm() {
            Some(perm) => {
                let (forward, inverse) = perm.arrays();
                (forward.to_vec(), inverse.to_vec())
            }
            None => ((0..n).collect(), (0..n).collect()),
        };
        let SymbolicCholeskyRaw::Supernodal(supernodal) = symbolic.raw() else {
            return None;
        };
        let count = supernodal.n_supernodes();
        let rows = supernodal.row_idx().to_vec();
        let row_starts = supernodal.col_ptr_for_row_idx();
        let mut front_of = vec![0usize; n];
        let (mut factor_len, mut schur_len) = (0usize, 0usize);
        let mut fronts = Vec::with_capacity(count);
        for t in 0..count {
            let (begin, end) = (
                supernodal.supernode_begin()[t],
                supernodal.supernode_end()[t],
            );
            front_of[begin..end].fill(t);
            let (k, range) = (end - begin, row_starts[t]..row_starts[t + 1]);
            let r = range.len();
            fronts.push(Front {
                begin,
                end,
                rows: range,
                lower: factor_len,
                upper: factor_len + (k + r) * k,
                schur: schur_len,
                parent: None,
                relative: Vec::new(),
            });
            factor_len += (k + r) * k + k * r;
            schur_len += r * r;
        }
        // Multiply-adds of the fronts' eliminations and Schur complements, per stored entry.
        let work: usize = fronts
            .iter()
            .map(|f| f.width() * f.width() * (f.width() + f.below()) + f.width() * f.below().pow(2))
            .sum();
        if fronts.iter().any(|f| f.width() > MAX_FRONT_WIDTH)
            || (work as f64) < min_work_per_entry * factor_len as f64
        {
            return None;
        }
        let max_below = fronts.iter().map(Front::below).max().unwrap_or(0);
        for t in 0..count {
            let Some(&first) = rows[fronts[t].rows.clone()].first() else {
                continue;
            };
            let parent = front_of[first];
            let relative = rows[fronts[t].rows.clone()]
                .iter()
                .map(|&row| front_index(&fronts[parent], &rows, row))
                .collect::<Option<Vec<_>>>()?;
            fronts[t].parent = Some(parent);
            fronts[t].relative = relative;
        }
        let mut analysis = StaticLu {
            new_of_old,
            old_of_new,
            fronts,
            rows,
            assembly: Vec::with_capacity(pattern.nonzeros()),
            factors: vec![T::from(0.0); factor_len],
            schur: vec![T::from(0.0); schur_len],
            work: vec![T::from(0.0); n],
            below: vec![T::from(0.0); max_below],
            avx2: has_avx2(),
        };
        for column in 0..n {
            for &row in pattern.column(column) {
                let (i, j) = (analysis.new_of_old[row], analysis.new_of_old[column]);
                let owner = &analysis.fronts[front_of[i.min(j)]];
                let a = front_index(owner, &analysis.rows, i)?;
                let b = front_index(owner, &analysis.rows, j)?;
                analysis.assembly.push(position(owner, a, b)?);
            }
        }
        Some(analysis)
    }

    /// Factors the matrix whose stored entries (in the pattern's column order) are
    /// `values`.
    pub fn factor(&mut self, values: &[T]) -> Result<(), PivotRefused> {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is set only when the CPU has AVX2 (`has_avx2`).
            return unsafe { self.factor_avx2(values) };
        }
        self.factor_portable(values)
    }

    /// [`Self::factor`] with the kernels compiled for AVX2: four lanes where the portable
    /// build has two, the same operations in the same order (the factors are bit-identical).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn factor_avx2(&mut self, values: &[T]) -> Result<(), PivotRefused> {
        self.factor_portable(values)
    }

    #[inline(always)]
    fn factor_portable(&mut self, values: &[T]) -> Result<(), PivotRefused> {
        self.factors.fill(T::from(0.0));
        self.schur.fill(T::from(0.0));
        for (&slot, &value) in self.assembly.iter().zip(values) {
            self.factors[slot] += value;
        }
        for t in 0..self.fronts.len() {
            self.factor_front(t)?;
            self.extend_add(t);
        }
        Ok(())
    }

    /// Dense LU of front `t` without row exchanges, then its Schur complement.
    #[inline(always)]
    fn factor_front(&mut self, t: usize) -> Result<(), PivotRefused> {
        let front = &self.fronts[t];
        let (k, r) = (front.width(), front.below());
        let m = k + r;
        let (lower, rest) = self.factors[front.lower..].split_at_mut(m * k);
        let upper = &mut rest[..k * r];
        for p in 0..k {
            let pivot = lower[p + p * m];
            let largest = lower[p + 1 + p * m..(p + 1) * m]
                .iter()
                .map(|v| v.pivot_size())
                .fold(0.0, f64::max);
            if !pivot.is_usable_pivot() || pivot.pivot_size() < PIVOT_TOLERANCE * largest {
                return Err(PivotRefused);
            }
            let inverse = T::from(1.0) / pivot;
            lower[p + p * m] = inverse;
            for v in &mut lower[p + 1 + p * m..(p + 1) * m] {
                *v *= inverse;
            }
            let (left, right) = lower.split_at_mut((p + 1) * m);
            let column = &left[p + 1 + p * m..];
            for j in 0..k - p - 1 {
                let target = &mut right[j * m..(j + 1) * m];
                let factor = target[p];
                axpy(&mut target[p + 1..], column, factor);
            }
            // The last pivot's row of `U12` needs no update (and one-column fronts, the
            // most frequent, none at all).
            if p + 1 < k {
                for target in upper.chunks_exact_mut(k) {
                    let factor = target[p];
                    axpy(&mut target[p + 1..], &column[..k - p - 1], factor);
                }
            }
        }
        let schur = &mut self.schur[front.schur..front.schur + r * r];
        schur_update(schur, &lower[k..], m, upper, k, r);
        Ok(())
    }

    /// Adds front `t`'s Schur complement into its parent's front.
    #[inline(always)]
    fn extend_add(&mut self, t: usize) {
        let front = &self.fronts[t];
        let Some(parent) = front.parent else {
            return;
        };
        let r = front.below();
        let target = &self.fronts[parent];
        let (kp, rp) = (target.width(), target.below());
        // The relative indices ascend: those in the parent's diagonal block come first.
        let split = front.relative.partition_point(|&a| a < kp);
        // The parent's Schur block lies after the child's (fronts are numbered children
        // first).
        let (source, parent_schur) = self.schur.split_at_mut(target.schur);
        let targets = &mut self.factors;
        for (jj, &b) in front.relative.iter().enumerate() {
            let column = &source[front.schur + jj * r..front.schur + (jj + 1) * r];
            if b < kp {
                let base = target.lower + b * (kp + rp);
                for (&a, &value) in front.relative.iter().zip(column) {
                    targets[base + a] += value;
                }
                continue;
            }
            let base = target.upper + (b - kp) * kp;
            for (&a, &value) in front.relative[..split].iter().zip(column) {
                targets[base + a] += value;
            }
            let base = (b - kp) * rp;
            for (&a, &value) in front.relative[split..].iter().zip(&column[split..]) {
                parent_schur[base + a - kp] += value;
            }
        }
    }

    /// Solves `A x = b` in place with the last factorization.
    pub fn solve(&mut self, rhs: &mut [T]) {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is set only when the CPU has AVX2 (`has_avx2`).
            return unsafe { self.solve_avx2(rhs) };
        }
        self.solve_portable(rhs)
    }

    /// [`Self::solve`] with the kernels compiled for AVX2 (bit-identical results).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn solve_avx2(&mut self, rhs: &mut [T]) {
        self.solve_portable(rhs)
    }

    #[inline(always)]
    fn solve_portable(&mut self, rhs: &mut [T]) {
        for (new, &old) in self.old_of_new.iter().enumerate() {
            self.work[new] = rhs[old];
        }
        let (y, below) = (&mut self.work, &mut self.below);
        for front in &self.fronts {
            let (k, r) = (front.width(), front.below());
            let m = k + r;
            let lower = &self.factors[front.lower..front.lower + m * k];
            let rows = &self.rows[front.rows.clone()];
            let below = &mut below[..r];
            below.fill(T::from(0.0));
            let own = &mut y[front.begin..front.end];
            for p in 0..k {
                let x = own[p];
                let column = &lower[p * m..(p + 1) * m];
                axpy(&mut own[p + 1..], &column[p + 1..k], x);
                axpy(below, &column[k..], x);
            }
            for (&row, &value) in rows.iter().zip(below.iter()) {
                y[row] += value;
            }
        }
        for front in self.fronts.iter().rev() {
            let (k, r) = (front.width(), front.below());
            let m = k + r;
            let lower = &self.factors[front.lower..front.lower + m * k];
            let upper = &self.factors[front.upper..front.upper + k * r];
            let rows = &self.rows[front.rows.clone()];
            match k {
                1 => subtract_upper::<T, 1>(y, front.begin, upper, rows),
                2 => subtract_upper::<T, 2>(y, front.begin, upper, rows),
                3 => subtract_upper::<T, 3>(y, front.begin, upper, rows),
                4 => subtract_upper::<T, 4>(y, front.begin, upper, rows),
                _ => {
                    for (column, &row) in upper.chunks_exact(k).zip(rows) {
                        let x = y[row];
                        axpy(&mut y[front.begin..front.end], column, x);
                    }
                }
            }
            let own = &mut y[front.begin..front.end];
            for p in (0..k).rev() {
                let x = own[p] * lower[p + p * m];
                own[p] = x;
                axpy(&mut own[..p], &lower[p * m..p * m + p], x);
            }
        }
        for (new, &old) in self.old_of_new.iter().enumerate() {
            rhs[old] = self.work[new];
        }
    }
}

/// `S -= L21 U12` for an `r × r` block `S`, `L21` the `r × k` block at `lower` (column
/// stride `m`) and `U12` the `k × r` block `upper`: four columns of `S` at a time, so that
/// each load of `L21` serves four of them.
#[inline(always)]
fn schur_update<T: LuScalar>(
    schur: &mut [T],
    lower: &[T],
    m: usize,
    upper: &[T],
    k: usize,
    r: usize,
) {
    if r == 0 {
        return;
    }
    let mut blocks = schur.chunks_exact_mut(4 * r);
    for (block, j) in (&mut blocks).zip((0..).step_by(4)) {
        let (s0, rest) = block.split_at_mut(r);
        let (s1, rest) = rest.split_at_mut(r);
        let (s2, s3) = rest.split_at_mut(r);
        for p in 0..k {
            let l = &lower[p * m..p * m + r];
            let u = [
                upper[p + j * k],
                upper[p + (j + 1) * k],
                upper[p + (j + 2) * k],
                upper[p + (j + 3) * k],
            ];
            for i in 0..r {
                let li = l[i];
                s0[i] -= li * u[0];
                s1[i] -= li * u[1];
                s2[i] -= li * u[2];
                s3[i] -= li * u[3];
            }
        }
    }
    let done = r - blocks.into_remainder().len() / r;
    for j in done..r {
        let target = &mut schur[j * r..(j + 1) * r];
        for p in 0..k {
            axpy(target, &lower[p * m..p * m + r], upper[p + j * k]);
        }
    }
}

/// `y[begin..begin + K] -= U12 y[rows]` for a front of `K` columns (`upper` its `K × r`
/// block, column by column): the `K` values stay in registers over the rows, where an
/// `axpy` of length `K` per row would cost more in loop set-up than in arithmetic (most
/// fronts of a 2-D grid's analysis have 1 to 4 columns). The same operations in the same
/// order as the `axpy` per row.
#[inline(always)]
fn subtract_upper<T: LuScalar, const K: usize>(
    y: &mut [T],
    begin: usize,
    upper: &[T],
    rows: &[usize],
) {
    let own = &mut y[begin..begin + K];
    let mut values: [T; K] = std::array::from_fn(|p| own[p]);
    for (column, &row) in upper.chunks_exact(K).zip(rows) {
        let x = y[row];
        for p in 0..K {
            values[p] -= column[p] * x;
        }
    }
    y[begin..begin + K].copy_from_slice(&values);
}

/// `target -= source * factor`.
#[inline(always)]
fn axpy<T: LuScalar>(target: &mut [T], source: &[T], factor: T) {
    for (t, &s) in target.iter_mut().zip(source) {
        *t -= s * factor;
    }
}

/// Whether the CPU has AVX2 (x86-64 only): the factorization and the solves then run
/// their AVX2 builds. No instruction differs in rounding (no fused multiply-add), so the
/// results are the same bit for bit on every CPU.
fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// The index of unknown `row` (elimination order) in `front`: its columns first, then its
/// rows below.
fn front_index(front: &Front, rows: &[usize], row: usize) -> Option<usize> {
    if (front.begin..front.end).contains(&row) {
        return Some(row - front.begin);
    }
    rows[front.rows.clone()]
        .binary_search(&row)
        .ok()
        .map(|i| front.width() + i)
}

/// Where entry `(a, b)` of `front` (front indices) is stored in `factors`; `None` for the
/// Schur block (both indices below the diagonal block).
fn position(front: &Front, a: usize, b: usize) -> Option<usize> {
    let (k, m) = (front.width(), front.width() + front.below());
    if b < k {
        Some(front.lower + a + b * m)
    } else if a < k {
        Some(front.upper + a + (b - k) * k)
    } else {
        None
    }
}

/// `pattern + patternᵀ` with the diagonal, as column starts and sorted row indices.
fn symmetrized(pattern: &SparsityPattern) -> (Vec<usize>, Vec<usize>) {
    let n = pattern.size();
    let mut counts = vec![1usize; n];
    for j in 0..n {
        for &i in pattern.column(j) {
            if i != j {
                counts[j] += 1;
                counts[i] += 1;
            }
        }
    }
    let mut starts = Vec::with_capacity(n + 1);
    starts.push(0);
    for j in 0..n {
        starts.push(starts[j] + counts[j]);
    }
    let mut fill = starts[..n].to_vec();
    let mut indices = vec![0usize; starts[n]];
    let mut push = |column: usize, row: usize| {
        indices[fill[column]] = row;
        fill[column] += 1;
    };
    for j in 0..n {
        push(j, j);
        for &i in pattern.column(j) {
            if i != j {
                push(j, i);
                push(i, j);
            }
        }
    }
    // Sort and deduplicate each column, compacting in place.
    let mut compact = Vec::with_capacity(n + 1);
    compact.push(0);
    let mut write = 0;
    for j in 0..n {
        let (begin, end) = (starts[j], starts[j + 1]);
        indices[begin..end].sort_unstable();
        let mut last = usize::MAX;
        for k in begin..end {
            if indices[k] != last {
                last = indices[k];
                indices[write] = last;
                write += 1;
            }
        }
        compact.push(write);
    }
    indices.truncate(write);
    (compact, indices)
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::c64;

    /// A 2-D periodic grid with two coupled species (BRUSS2D's structure) plus one
    /// unsymmetric entry.
    fn grid(n: usize, shift: f64) -> (SparsityPattern, Vec<(usize, usize, f64)>) {
        let idx = |c: usize, i: usize, j: usize| c * n * n + i * n + j;
        let mut entries = Vec::new();
        for i in 0..n {
            for j in 0..n {
                for c in 0..2 {
                    let row = idx(c, i, j);
                    for (di, dj) in [(1, 0), (n - 1, 0), (0, 1), (0, n - 1)] {
                        entries.push((
                            row,
                            idx(c, (i + di) % n, (j + dj) % n),
                            -1.0 - 0.01 * c as f64,
                        ));
                    }
                }
                entries.push((idx(0, i, j), idx(0, i, j), shift + (i as f64).sin()));
                entries.push((idx(0, i, j), idx(1, i, j), -0.5));
                entries.push((idx(1, i, j), idx(0, i, j), 1.5 + (j as f64).cos()));
                entries.push((idx(1, i, j), idx(1, i, j), shift + 1.0));
            }
        }
        entries.push((0, 2 * n * n - 1, 0.3));
        let pattern =
            SparsityPattern::from_entries(2 * n * n, entries.iter().map(|(i, j, _)| (*i, *j)))
                .unwrap();
        (pattern, entries)
    }

    fn values_of(pattern: &SparsityPattern, entries: &[(usize, usize, f64)]) -> Vec<f64> {
        let mut values = vec![0.0; pattern.nonzeros()];
        for &(i, j, v) in entries {
            values[pattern.position(i, j).unwrap()] += v;
        }
        values
    }

    /// The residual of a solve, real and complex, on two grids.
    #[test]
    fn solves_grid_systems() {
        for n in [7, 16] {
            let (pattern, entries) = grid(n, 10.0);
            let values = values_of(&pattern, &entries);
            let size = pattern.size();
            let b: Vec<f64> = (0..size).map(|i| (i as f64 * 0.37).sin()).collect();
            let mut lu = StaticLu::<f64>::analyze(&pattern, 0.0).unwrap();
            lu.factor(&values).unwrap();
            let mut x = b.clone();
            lu.solve(&mut x);
            let mut residual = b.clone();
            for &(i, j, v) in &entries {
                residual[i] -= v * x[j];
            }
            let worst = residual.iter().fold(0.0f64, |a, r| a.max(r.abs()));
            assert!(worst < 1e-12, "{n}: residual {worst}");
            // The same matrix plus 3i on the diagonal.
            let mut complex: Vec<c64> = values.iter().map(|&v| c64::new(v, 0.0)).collect();
            for i in 0..size {
                complex[pattern.position(i, i).unwrap()] += c64::new(0.0, 3.0);
            }
            let mut lu = StaticLu::<c64>::analyze(&pattern, 0.0).unwrap();
            lu.factor(&complex).unwrap();
            let mut z: Vec<c64> = b.iter().map(|&v| c64::new(v, -v)).collect();
            lu.solve(&mut z);
            let mut residual: Vec<c64> = b.iter().map(|&v| c64::new(v, -v)).collect();
            for &(i, j, v) in &entries {
                residual[i] -= c64::new(v, 0.0) * z[j];
            }
            for i in 0..size {
                residual[i] -= c64::new(0.0, 3.0) * z[i];
            }
            let worst = residual.iter().fold(0.0f64, |a, r| a.max(r.norm()));
            assert!(worst < 1e-12, "{n}: complex residual {worst}");
        }
    }

    /// The portable build of the kernels and the AVX2 one (where the CPU has it) give the
    /// same factors and solutions, bit for bit, real and complex; the portable one is
    /// otherwise never run on an AVX2 machine.
    #[test]
    fn the_portable_and_the_avx2_kernels_agree_bit_for_bit() {
        fn run<T: LuScalar>(
            pattern: &SparsityPattern,
            values: &[T],
            b: &[T],
            avx2: bool,
        ) -> Vec<T> {
            let mut lu = StaticLu::<T>::analyze(pattern, 0.0).unwrap();
            lu.avx2 = avx2 && has_avx2();
            lu.factor(values).unwrap();
            let mut x = b.to_vec();
            lu.solve(&mut x);
            lu.factors.iter().copied().chain(x).collect()
        }
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for n in [7, 16] {
            let (pattern, entries) = grid(n, 10.0);
            let values = values_of(&pattern, &entries);
            let b: Vec<f64> = (0..pattern.size())
                .map(|i| (i as f64 * 0.37).sin())
                .collect();
            let (portable, wide) = (
                run(&pattern, &values, &b, false),
                run(&pattern, &values, &b, true),
            );
            assert_eq!(bits(&portable), bits(&wide), "{n}: real");
            let complex: Vec<c64> = values.iter().map(|&v| c64::new(v, 0.5 * v)).collect();
            let cb: Vec<c64> = b.iter().map(|&v| c64::new(v, -v)).collect();
            let split = |v: Vec<c64>| v.iter().flat_map(|z| [z.re, z.im]).collect::<Vec<_>>();
            let portable = split(run(&pattern, &complex, &cb, false));
            let wide = split(run(&pattern, &complex, &cb, true));
            assert_eq!(bits(&portable), bits(&wide), "{n}: complex");
        }
    }

    #[test]
    fn a_small_pivot_is_refused() {
        let (pattern, mut entries) = grid(4, 10.0);
        // Row and column 5: a zero diagonal.
        for e in &mut entries {
            if e.0 == 5 && e.1 == 5 {
                e.2 = 0.0;
            }
        }
        let values = values_of(&pattern, &entries);
        let mut lu = StaticLu::<f64>::analyze(&pattern, 0.0).unwrap();
        assert_eq!(lu.factor(&values), Err(PivotRefused));
    }
}
