//! The Jacobian `df/dx` for the implicit methods: analytic when the system provides it,
//! otherwise forward differences — column by column for dense systems, or by groups of
//! structurally orthogonal columns (greedy column coloring) when a sparsity pattern is known.
//!
//! Increment of column `j`: `sqrt(eps) * max(|x_j|, scale_j, 1e-5)` with
//! `scale_j = atol_j + rtol_j |x_j|`, rounded so that `x_j + inc` is exact.

use crate::error::EvalError;
use crate::evaluate::rhs_checked;
use crate::stats::Stats;
use crate::system::{JacobianMatrix, SparsityPattern, System};

/// Holds the Jacobian storage and the scratch for finite differences.
#[derive(Debug, Clone)]
pub(crate) struct JacobianEvaluator {
    matrix: JacobianMatrix,
    /// Columns grouped by color (with a pattern, computed at the first differences: a
    /// system with an analytic Jacobian never needs them); `None` means one column at a
    /// time.
    color_groups: Option<Vec<Vec<usize>>>,
    pattern: Option<SparsityPattern>,
    x_perturbed: Vec<f64>,
    f_perturbed: Vec<f64>,
    increments: Vec<f64>,
}

impl JacobianEvaluator {
    /// Sparse storage when `sparse_storage` and the system has a pattern, dense otherwise.
    pub fn new(system: &dyn System, sparse_storage: bool) -> Self {
        let size = system.len();
        let pattern = system.sparsity().cloned();
        let matrix = match (&pattern, sparse_storage) {
            (Some(pattern), true) => JacobianMatrix::sparse(pattern.clone()),
            (None, true) => JacobianMatrix::sparse(SparsityPattern::dense(size)),
            _ => JacobianMatrix::dense(size),
        };
        JacobianEvaluator {
            matrix,
            color_groups: None,
            pattern,
            x_perturbed: vec![0.0; size],
            f_perturbed: vec![0.0; size],
            increments: vec![0.0; size],
        }
    }

    pub fn matrix(&self) -> &JacobianMatrix {
        &self.matrix
    }

    /// Evaluates `df/dx` at `(t, x)`; `f_at_x` must be `f(t, x)` and `scale` the tolerance
    /// scales used for the increments.
    pub fn evaluate(
        &mut self,
        system: &mut dyn System,
        t: f64,
        x: &[f64],
        f_at_x: &[f64],
        scale: &[f64],
        stats: &mut Stats,
    ) -> Result<(), EvalError> {
        stats.jacobian_evals += 1;
        self.matrix.fill_zero();
        if system.jacobian(t, x, &mut self.matrix)? {
            if !self.matrix.all_finite() {
                return Err(EvalError::failed(
                    "analytic Jacobian has a non-finite entry",
                ));
            }
            return Ok(());
        }
        self.matrix.fill_zero();
        for (j, increment) in self.increments.iter_mut().enumerate() {
            let raw = f64::EPSILON.sqrt() * x[j].abs().max(scale[j]).max(1e-5);
            *increment = (x[j] + raw) - x[j];
        }
        if self.color_groups.is_none() {
            self.color_groups = self.pattern.as_ref().map(color_columns);
        }
        match self.color_groups.take() {
            Some(groups) => {
                let result = self.colored_differences(system, t, x, f_at_x, &groups, stats);
                self.color_groups = Some(groups);
                result
            }
            None => self.column_differences(system, t, x, f_at_x, stats),
        }
    }

    fn column_differences(
        &mut self,
        system: &mut dyn System,
        t: f64,
        x: &[f64],
        f_at_x: &[f64],
        stats: &mut Stats,
    ) -> Result<(), EvalError> {
        self.x_perturbed.copy_from_slice(x);
        for j in 0..x.len() {
            let increment = self.increments[j];
            self.x_perturbed[j] = x[j] + increment;
            rhs_checked(system, t, &self.x_perturbed, &mut self.f_perturbed, stats)?;
            self.x_perturbed[j] = x[j];
            for i in 0..x.len() {
                let derivative = (self.f_perturbed[i] - f_at_x[i]) / increment;
                if derivative != 0.0 {
                    self.matrix.set(i, j, derivative);
                }
            }
        }
        Ok(())
    }

    fn colored_differences(
        &mut self,
        system: &mut dyn System,
        t: f64,
        x: &[f64],
        f_at_x: &[f64],
        groups: &[Vec<usize>],
        stats: &mut Stats,
    ) -> Result<(), EvalError> {
        let Some(pattern) = self.pattern.take() else {
            return Ok(());
        };
        self.x_perturbed.copy_from_slice(x);
        let mut result = Ok(());
        for group in groups {
            for &j in group {
                self.x_perturbed[j] = x[j] + self.increments[j];
            }
            result = rhs_checked(system, t, &self.x_perturbed, &mut self.f_perturbed, stats);
            for &j in group {
                self.x_perturbed[j] = x[j];
            }
            if result.is_err() {
                break;
            }
            for &j in group {
                for &i in pattern.column(j) {
                    let derivative = (self.f_perturbed[i] - f_at_x[i]) / self.increments[j];
                    self.matrix.set(i, j, derivative);
                }
            }
        }
        self.pattern = Some(pattern);
        result
    }
}

/// Greedy coloring: columns of one color share no row, so one evaluation of `f` with all of
/// them perturbed gives each column's differences.
pub(crate) fn color_columns(pattern: &SparsityPattern) -> Vec<Vec<usize>> {
    let size = pattern.size();
    let mut columns_of_row: Vec<Vec<usize>> = vec![Vec::new(); size];
    for j in 0..size {
        for &i in pattern.column(j) {
            columns_of_row[i].push(j);
        }
    }
    let mut color_of_column: Vec<Option<usize>> = vec![None; size];
    let mut forbidden_stamp: Vec<usize> = Vec::new();
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for j in 0..size {
        for &i in pattern.column(j) {
            for &k in &columns_of_row[i] {
                if let Some(color) = color_of_column[k] {
                    forbidden_stamp[color] = j + 1;
                }
            }
        }
        let color = (0..groups.len())
            .find(|&c| forbidden_stamp[c] != j + 1)
            .unwrap_or_else(|| {
                groups.push(Vec::new());
                forbidden_stamp.push(0);
                groups.len() - 1
            });
        color_of_column[j] = Some(color);
        groups[color].push(j);
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tridiagonal_needs_three_colors() {
        let size: usize = 10;
        let entries = (0..size).flat_map(|j: usize| {
            [j.wrapping_sub(1), j, j + 1]
                .into_iter()
                .filter(move |&i| i < size)
                .map(move |i| (i, j))
        });
        let pattern = SparsityPattern::from_entries(size, entries).unwrap();
        let groups = color_columns(&pattern);
        assert_eq!(groups.len(), 3);
        assert_eq!(groups[0], vec![0, 3, 6, 9]);
    }
}
