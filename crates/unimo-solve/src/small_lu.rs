//! A small dense LU with partial pivoting for the iteration matrices `shift * M - J` of
//! the implicit methods below `linear::SMALL_DENSE_LIMIT` unknowns, real or complex:
//! row-major factors in preallocated storage, unblocked elimination, no allocation when
//! factoring or solving. On an 18 x 18 matrix it takes a fraction of the instructions of
//! faer's blocked LU, whose set-up and recursion dominate at this size.

use crate::linear::{LuScalar, ShiftedMatrix, SingularMatrix};

/// The factors `P A = L U` of one square matrix (`L` unit lower, both in `factors`).
#[derive(Debug, Clone)]
pub(crate) struct SmallLu<T: LuScalar> {
    size: usize,
    /// Row-major `size × size`: `U` on and above the diagonal, `L` below it.
    factors: Vec<T>,
    /// The row interchanges, as LAPACK's `ipiv`: at elimination step `k`, row `k` was
    /// swapped with row `swaps[k] >= k` (applied to the right-hand side in place: no
    /// gather into scratch and copy back).
    swaps: Vec<usize>,
    /// `1 / U_kk`: the solve multiplies (a division on the back substitution's chain of
    /// dependent rows costs several times a multiplication, a complex one far more).
    inverse_pivots: Vec<T>,
}

impl<T: LuScalar> SmallLu<T> {
    pub fn new(size: usize) -> Self {
        SmallLu {
            size,
            factors: vec![T::from(0.0); size * size],
            swaps: (0..size).collect(),
            inverse_pivots: vec![T::from(1.0); size],
        }
    }

    /// The matrices' size.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Writes `matrix` into the factors' storage and factors it.
    pub fn factor_shifted(&mut self, matrix: ShiftedMatrix<'_, T>) -> Result<(), SingularMatrix> {
        let n = self.size;
        self.factors.fill(T::from(0.0));
        let factors = &mut self.factors;
        matrix.for_each_term(|i, j, value| factors[i * n + j] += value);
        self.factor()
    }

    /// Factors the matrix held in `factors` in place.
    fn factor(&mut self) -> Result<(), SingularMatrix> {
        let n = self.size;
        let a = &mut self.factors[..n * n];
        for k in 0..n {
            let mut pivot_row = k;
            let mut best = a[k * n + k].pivot_size();
            for i in k + 1..n {
                let size = a[i * n + k].pivot_size();
                if size > best {
                    best = size;
                    pivot_row = i;
                }
            }
            if !(best > 0.0 && best.is_finite()) {
                return Err(SingularMatrix);
            }
            self.swaps[k] = pivot_row;
            if pivot_row != k {
                let (upper, lower) = a.split_at_mut(pivot_row * n);
                upper[k * n..(k + 1) * n].swap_with_slice(&mut lower[..n]);
            }
            let (upper, lower) = a.split_at_mut((k + 1) * n);
            let pivot = &upper[k * n + k..(k + 1) * n];
            // LAPACK's getf2 scales by the reciprocal as well.
            let inverse = T::from(1.0) / pivot[0];
            if !inverse.is_usable_pivot() {
                // A subnormal pivot: its reciprocal overflows.
                return Err(SingularMatrix);
            }
            self.inverse_pivots[k] = inverse;
            for row in lower.chunks_exact_mut(n) {
                let row = &mut row[k..];
                let f = row[0] * inverse;
                row[0] = f;
                if f != T::from(0.0) {
                    for (x, &y) in row[1..].iter_mut().zip(&pivot[1..]) {
                        *x -= f * y;
                    }
                }
            }
        }
        Ok(())
    }

    /// Solves `A x = b` in place with the last factorization.
    pub fn solve(&mut self, b: &mut [T]) {
        let n = self.size;
        let a = &self.factors[..n * n];
        let y = &mut b[..n];
        for (k, &swap) in self.swaps.iter().enumerate() {
            y.swap(k, swap);
        }
        // L y = P b (unit diagonal), row by row.
        for i in 1..n {
            let row = &a[i * n..i * n + i];
            let mut s = y[i];
            for (&l, &yj) in row.iter().zip(&y[..i]) {
                s -= l * yj;
            }
            y[i] = s;
        }
        // U x = y, from the last row up.
        for i in (0..n).rev() {
            let row = &a[i * n + i + 1..(i + 1) * n];
            let mut s = y[i];
            for (&u, &xj) in row.iter().zip(&y[i + 1..]) {
                s -= u * xj;
            }
            y[i] = s * self.inverse_pivots[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linear::ShiftedLu;
    use crate::system::JacobianMatrix;
    use faer::c64;

    /// A deterministic pseudo-random `n × n` Jacobian (xorshift), some entries zero.
    fn random_jacobian(n: usize, seed: u64) -> JacobianMatrix {
        let mut s = seed;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s % 2001) as f64 / 1000.0 - 1.0
        };
        let mut jacobian = JacobianMatrix::dense(n);
        for i in 0..n {
            for j in 0..n {
                let v = next();
                if v.abs() > 0.3 {
                    assert!(jacobian.set(i, j, 10.0 * v));
                }
            }
        }
        jacobian
    }

    #[test]
    fn agrees_with_faer_on_real_and_complex_shifts() {
        for (n, seed) in [(1, 3), (5, 7), (18, 11), (31, 13)] {
            let jacobian = random_jacobian(n, seed);
            let differential: Vec<bool> = (0..n).map(|i| i % 4 != 3).collect();
            let mut small = ShiftedLu::<f64>::dense(n);
            let mut faer = ShiftedLu::<f64>::faer_dense(n);
            small.factor(&jacobian, &differential, 3.5).unwrap();
            faer.factor(&jacobian, &differential, 3.5).unwrap();
            let b: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
            let (mut x, mut y) = (b.clone(), b.clone());
            small.solve(&mut x);
            faer.solve(&mut y);
            let scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
            for i in 0..n {
                assert!((x[i] - y[i]).abs() <= 1e-12 * scale, "n {n} row {i}");
            }
            let shift = c64::new(2.0, -1.5);
            let mut small = ShiftedLu::<c64>::dense(n);
            let mut faer = ShiftedLu::<c64>::faer_dense(n);
            small.factor(&jacobian, &differential, shift).unwrap();
            faer.factor(&jacobian, &differential, shift).unwrap();
            let b: Vec<c64> = (0..n).map(|i| c64::new(1.0, i as f64)).collect();
            let (mut x, mut y) = (b.clone(), b.clone());
            small.solve(&mut x);
            faer.solve(&mut y);
            let scale = y.iter().fold(1.0f64, |m, v| m.max(v.norm()));
            for i in 0..n {
                assert!((x[i] - y[i]).norm() <= 1e-12 * scale, "n {n} row {i}");
            }
        }
    }

    /// A subnormal pivot passes the nonzero test, but its reciprocal (which the solve
    /// multiplies by) overflows: the matrix is reported singular, not solved into infinities.
    #[test]
    fn subnormal_pivot_is_singular() {
        let mut jacobian = JacobianMatrix::dense(2);
        assert!(jacobian.set(0, 0, -1.0));
        assert!(jacobian.set(1, 1, -1e-310));
        let mut lu = ShiftedLu::<f64>::dense(2);
        assert_eq!(
            lu.factor(&jacobian, &[false, false], 1.0),
            Err(SingularMatrix)
        );
        // A tiny but normal pivot (a power of two: exact reciprocal) is factored and solved.
        let tiny = 2f64.powi(-1000);
        assert!(jacobian.set(1, 1, -tiny));
        assert_eq!(lu.factor(&jacobian, &[false, false], 1.0), Ok(()));
        let mut x = [2.0, 3.0 * tiny];
        lu.solve(&mut x);
        assert_eq!(x, [2.0, 3.0]);
    }

    #[test]
    fn zero_column_is_singular() {
        let mut jacobian = JacobianMatrix::dense(3);
        assert!(jacobian.set(0, 0, 1.0));
        assert!(jacobian.set(1, 1, 1.0));
        let mut lu = ShiftedLu::<f64>::dense(3);
        assert_eq!(
            lu.factor(&jacobian, &[false, false, false], 1.0),
            Err(SingularMatrix)
        );
    }
}
