//! The problem interface: a semi-explicit index-1 DAE `M x' = f(t, x)` whose mass matrix `M`
//! is diagonal with entries 1 (differential rows) and 0 (algebraic rows, `0 = f_i(t, x)`),
//! plus optional analytic Jacobian, sparsity pattern and zero-crossing functions.

use faer::{Mat, MatMut};

use crate::error::{EvalError, SolveError};

/// The system integrated by every method of this crate.
///
/// Row `i` is differential when `differential()[i]` is true (`x_i' = f_i(t, x)`) and
/// algebraic otherwise (`0 = f_i(t, x)`). Algebraic rows must form an index-1 system: the
/// block `df_alg/dx_alg` must be nonsingular along the solution.
pub trait System {
    /// Number of unknowns (and of equations).
    fn len(&self) -> usize;

    /// True when the system has no unknowns.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// One flag per row: true for differential rows (`M_ii = 1`), false for algebraic rows.
    fn differential(&self) -> &[bool];

    /// Evaluates `f(t, x)` into `out`.
    fn rhs(&mut self, t: f64, x: &[f64], out: &mut [f64]) -> Result<(), EvalError>;

    /// Fills the analytic Jacobian `df/dx` at `(t, x)` into `jacobian` (all entries are zero on
    /// entry). Returns `Ok(false)` to ask for finite differences instead (the default).
    fn jacobian(
        &mut self,
        t: f64,
        x: &[f64],
        jacobian: &mut JacobianMatrix,
    ) -> Result<bool, EvalError> {
        let _ = (t, x, jacobian);
        Ok(false)
    }

    /// Optional sparsity pattern of `df/dx`. With a pattern, finite-difference Jacobians use
    /// column coloring and large systems are factored with a sparse LU.
    fn sparsity(&self) -> Option<&SparsityPattern> {
        None
    }

    /// Number of zero-crossing functions.
    fn n_roots(&self) -> usize {
        0
    }

    /// Evaluates the zero-crossing functions `g(t, x)` into `out` (length `n_roots()`).
    fn roots(&mut self, t: f64, x: &[f64], out: &mut [f64]) -> Result<(), EvalError> {
        let _ = (t, x, out);
        Ok(())
    }

    /// Number of invariants `c(t, x) = 0` the solution keeps where they are active: the
    /// solver projects each accepted step's state onto them ([`crate::project`]).
    fn n_invariants(&self) -> usize {
        0
    }

    /// Evaluates the invariants `c(t, x)` into `out.values` and whether each holds now
    /// (is active) into `out.active` (both of length `n_invariants()`).
    fn invariants(&mut self, t: f64, x: &[f64], out: &mut Invariants) -> Result<(), EvalError> {
        let _ = (t, x, out);
        Ok(())
    }
}

/// The values of a system's invariants `c(t, x)` and whether each is active (holds now).
#[derive(Debug, Clone, Default)]
pub struct Invariants {
    pub values: Vec<f64>,
    pub active: Vec<bool>,
}

impl Invariants {
    /// Room for `m` invariants.
    pub(crate) fn resize(&mut self, m: usize) {
        self.values.resize(m, 0.0);
        self.active.resize(m, false);
    }
}

/// Column-compressed pattern of a square matrix: for each column, the sorted rows that may be
/// nonzero.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SparsityPattern {
    size: usize,
    column_starts: Vec<usize>,
    row_indices: Vec<usize>,
}

impl SparsityPattern {
    /// Builds a pattern of a `size × size` matrix from `(row, column)` entries (any order,
    /// duplicates allowed).
    pub fn from_entries(
        size: usize,
        entries: impl IntoIterator<Item = (usize, usize)>,
    ) -> Result<Self, SolveError> {
        // A counting sort by column (no vector a column), then each column's rows sorted
        // and deduplicated in place.
        let entries: Vec<(usize, usize)> = entries.into_iter().collect();
        let mut column_starts = vec![0usize; size + 1];
        for &(row, column) in &entries {
            if row >= size || column >= size {
                return Err(SolveError::invalid(format!(
                    "sparsity entry ({row}, {column}) outside a {size}x{size} matrix"
                )));
            }
            column_starts[column + 1] += 1;
        }
        for column in 0..size {
            column_starts[column + 1] += column_starts[column];
        }
        let mut next = column_starts.clone();
        let mut rows = vec![0usize; entries.len()];
        for &(row, column) in &entries {
            rows[next[column]] = row;
            next[column] += 1;
        }
        let mut row_indices = Vec::with_capacity(entries.len());
        let mut start = 0;
        for column in 0..size {
            let column_rows = &mut rows[start..column_starts[column + 1]];
            start = column_starts[column + 1];
            column_rows.sort_unstable();
            column_starts[column] = row_indices.len();
            let mut last = None;
            for &row in column_rows.iter() {
                if last != Some(row) {
                    row_indices.push(row);
                    last = Some(row);
                }
            }
        }
        column_starts[size] = row_indices.len();
        Ok(SparsityPattern {
            size,
            column_starts,
            row_indices,
        })
    }

    /// The dense pattern (every entry may be nonzero).
    pub fn dense(size: usize) -> Self {
        let entries = (0..size).flat_map(|column| (0..size).map(move |row| (row, column)));
        Self::from_entries(size, entries).unwrap_or_else(|_| unreachable_pattern())
    }

    /// Matrix dimension.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Number of structurally nonzero entries.
    pub fn nonzeros(&self) -> usize {
        self.row_indices.len()
    }

    /// Column start offsets into `row_indices` (length `size + 1`).
    pub fn column_starts(&self) -> &[usize] {
        &self.column_starts
    }

    /// Row indices of all columns, concatenated.
    pub fn row_indices(&self) -> &[usize] {
        &self.row_indices
    }

    /// Sorted rows of one column.
    pub fn column(&self, column: usize) -> &[usize] {
        &self.row_indices[self.column_starts[column]..self.column_starts[column + 1]]
    }

    /// Position of `(row, column)` in the value array, if it is in the pattern.
    pub fn position(&self, row: usize, column: usize) -> Option<usize> {
        if column >= self.size {
            return None;
        }
        let start = self.column_starts[column];
        self.column(column)
            .binary_search(&row)
            .ok()
            .map(|offset| start + offset)
    }

    /// The same pattern with the whole diagonal added (needed by `shift * M - J`).
    pub(crate) fn with_diagonal(&self) -> SparsityPattern {
        let entries = (0..self.size)
            .flat_map(|column| self.column(column).iter().map(move |&row| (row, column)))
            .chain((0..self.size).map(|i| (i, i)));
        Self::from_entries(self.size, entries).unwrap_or_else(|_| unreachable_pattern())
    }
}

/// Entries built from an existing valid pattern are always in range.
fn unreachable_pattern() -> SparsityPattern {
    SparsityPattern {
        size: 0,
        column_starts: vec![0],
        row_indices: Vec::new(),
    }
}

/// Storage for `df/dx` handed to [`System::jacobian`]: dense, or values on a sparsity pattern.
#[derive(Debug, Clone)]
pub struct JacobianMatrix {
    storage: JacobianStorage,
}

#[derive(Debug, Clone)]
enum JacobianStorage {
    Dense(Mat<f64>),
    Sparse {
        pattern: SparsityPattern,
        values: Vec<f64>,
    },
}

impl JacobianMatrix {
    /// A zero dense `size × size` matrix.
    pub fn dense(size: usize) -> Self {
        JacobianMatrix {
            storage: JacobianStorage::Dense(Mat::zeros(size, size)),
        }
    }

    /// A zero matrix with the given pattern.
    pub fn sparse(pattern: SparsityPattern) -> Self {
        let values = vec![0.0; pattern.nonzeros()];
        JacobianMatrix {
            storage: JacobianStorage::Sparse { pattern, values },
        }
    }

    /// Matrix dimension.
    pub fn size(&self) -> usize {
        match &self.storage {
            JacobianStorage::Dense(matrix) => matrix.nrows(),
            JacobianStorage::Sparse { pattern, .. } => pattern.size(),
        }
    }

    /// True for pattern storage.
    pub fn is_sparse(&self) -> bool {
        matches!(self.storage, JacobianStorage::Sparse { .. })
    }

    /// The pattern, for sparse storage.
    pub fn pattern(&self) -> Option<&SparsityPattern> {
        match &self.storage {
            JacobianStorage::Dense(_) => None,
            JacobianStorage::Sparse { pattern, .. } => Some(pattern),
        }
    }

    /// Sets one entry. Returns false (and drops the value) when `(row, column)` is outside the
    /// matrix or outside the sparsity pattern.
    pub fn set(&mut self, row: usize, column: usize, value: f64) -> bool {
        match &mut self.storage {
            JacobianStorage::Dense(matrix) => {
                if row < matrix.nrows() && column < matrix.ncols() {
                    matrix[(row, column)] = value;
                    true
                } else {
                    false
                }
            }
            JacobianStorage::Sparse { pattern, values } => match pattern.position(row, column) {
                Some(position) => {
                    values[position] = value;
                    true
                }
                None => false,
            },
        }
    }

    /// One entry (zero outside the pattern).
    pub fn get(&self, row: usize, column: usize) -> f64 {
        match &self.storage {
            JacobianStorage::Dense(matrix) => {
                if row < matrix.nrows() && column < matrix.ncols() {
                    matrix[(row, column)]
                } else {
                    0.0
                }
            }
            JacobianStorage::Sparse { pattern, values } => pattern
                .position(row, column)
                .map_or(0.0, |position| values[position]),
        }
    }

    /// Mutable dense view, for dense storage.
    pub fn dense_mut(&mut self) -> Option<MatMut<'_, f64>> {
        match &mut self.storage {
            JacobianStorage::Dense(matrix) => Some(matrix.as_mut()),
            JacobianStorage::Sparse { .. } => None,
        }
    }

    /// Pattern and mutable values (in pattern order), for sparse storage.
    pub fn sparse_values_mut(&mut self) -> Option<(&SparsityPattern, &mut [f64])> {
        match &mut self.storage {
            JacobianStorage::Dense(_) => None,
            JacobianStorage::Sparse { pattern, values } => Some((pattern, values.as_mut_slice())),
        }
    }

    /// Sets every entry to zero.
    pub fn fill_zero(&mut self) {
        match &mut self.storage {
            JacobianStorage::Dense(matrix) => matrix.fill(0.0),
            JacobianStorage::Sparse { values, .. } => values.fill(0.0),
        }
    }

    /// Sets every entry of the flagged rows to zero.
    pub(crate) fn zero_rows(&mut self, rows: &[bool]) {
        match &mut self.storage {
            JacobianStorage::Dense(matrix) => {
                for (i, _) in rows.iter().enumerate().filter(|(_, zero)| **zero) {
                    for j in 0..matrix.ncols() {
                        matrix[(i, j)] = 0.0;
                    }
                }
            }
            JacobianStorage::Sparse { pattern, values } => {
                for j in 0..pattern.size() {
                    let start = pattern.column_starts()[j];
                    for (offset, &i) in pattern.column(j).iter().enumerate() {
                        if rows[i] {
                            values[start + offset] = 0.0;
                        }
                    }
                }
            }
        }
    }

    /// True when every stored entry is finite.
    pub(crate) fn all_finite(&self) -> bool {
        match &self.storage {
            JacobianStorage::Dense(matrix) => {
                (0..matrix.ncols()).all(|j| (0..matrix.nrows()).all(|i| matrix[(i, j)].is_finite()))
            }
            JacobianStorage::Sparse { values, .. } => values.iter().all(|v| v.is_finite()),
        }
    }

    /// Calls `visit(row, column, value)` for every stored entry.
    pub(crate) fn for_each_entry(&self, mut visit: impl FnMut(usize, usize, f64)) {
        match &self.storage {
            JacobianStorage::Dense(matrix) => {
                for j in 0..matrix.ncols() {
                    for i in 0..matrix.nrows() {
                        visit(i, j, matrix[(i, j)]);
                    }
                }
            }
            JacobianStorage::Sparse { pattern, values } => {
                for j in 0..pattern.size() {
                    let start = pattern.column_starts()[j];
                    for (offset, &i) in pattern.column(j).iter().enumerate() {
                        visit(i, j, values[start + offset]);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::SparsityPattern;

    #[test]
    fn entries_in_any_order_with_duplicates_give_sorted_columns() {
        let entries = [(2, 0), (0, 0), (2, 0), (1, 2), (0, 2), (3, 3), (1, 2)];
        let pattern = SparsityPattern::from_entries(4, entries).unwrap();
        assert_eq!(pattern.column_starts(), &[0, 2, 2, 4, 5]);
        assert_eq!(pattern.row_indices(), &[0, 2, 0, 1, 3]);
        assert_eq!(pattern.position(1, 2), Some(3));
        assert_eq!(pattern.position(1, 1), None);
        assert!(SparsityPattern::from_entries(2, [(0, 2)]).is_err());
        let empty = SparsityPattern::from_entries(3, []).unwrap();
        assert_eq!(
            (empty.column_starts(), empty.nonzeros()),
            (&[0, 0, 0, 0][..], 0)
        );
    }
}
