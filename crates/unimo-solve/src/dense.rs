//! Small dense linear algebra for the algebraic parts of a simulation: LU with partial
//! pivoting for Newton's steps, determinants and rank-revealing choices of rows and
//! columns (consistent initialization, dynamic state selection). Matrices are row-major
//! slices; nothing here allocates on the hot path except where a result is returned.

/// Solves `a x = b` in place (LU with partial pivoting); false when singular.
pub fn lu_solve(n: usize, a: &mut [f64], b: &mut [f64], perm: &mut [usize]) -> bool {
    for (i, p) in perm.iter_mut().enumerate().take(n) {
        *p = i;
    }
    let (a, b) = (&mut a[..n * n], &mut b[..n]);
    for k in 0..n {
        let mut piv = k;
        let mut best = a[k * n + k].abs();
        for (i, row) in a.chunks_exact(n).enumerate().skip(k + 1) {
            let v = row[k].abs();
            if v > best {
                best = v;
                piv = i;
            }
        }
        if best == 0.0 || !best.is_finite() {
            return false;
        }
        if piv != k {
            let (upper, lower) = a.split_at_mut(piv * n);
            upper[k * n..(k + 1) * n].swap_with_slice(&mut lower[..n]);
            b.swap(k, piv);
            perm.swap(k, piv);
        }
        // Rows below k minus multiples of row k (slices: no index checks inside).
        let (upper, lower) = a.split_at_mut((k + 1) * n);
        let pivot_row = &upper[k * n + k..];
        let (d, bk) = (pivot_row[0], b[k]);
        for (row, bi) in lower.chunks_exact_mut(n).zip(&mut b[k + 1..]) {
            let f = row[k] / d;
            if f != 0.0 {
                row[k] = f;
                for (x, &y) in row[k + 1..].iter_mut().zip(&pivot_row[1..]) {
                    *x -= f * y;
                }
                *bi -= f * bk;
            }
        }
    }
    back_substitute(n, a, b);
    true
}

/// Solves `a x = b` in place with the factors [`lu_solve`] left in `a` and `perm` (the
/// same matrix, another right-hand side: iterative refinement).
pub fn lu_resolve(n: usize, a: &[f64], perm: &[usize], b: &mut [f64], work: &mut Vec<f64>) {
    work.clear();
    work.extend(perm[..n].iter().map(|&p| b[p]));
    let b = &mut b[..n];
    b.copy_from_slice(work);
    for k in 0..n {
        let bk = b[k];
        for (i, bi) in b.iter_mut().enumerate().skip(k + 1) {
            *bi -= a[i * n + k] * bk;
        }
    }
    back_substitute(n, a, b);
}

/// `U x = b` in place, `U` the upper triangle of the row-major `n x n` factors `a`.
fn back_substitute(n: usize, a: &[f64], b: &mut [f64]) {
    for k in (0..n).rev() {
        let row = &a[k * n..(k + 1) * n];
        let s = row[k + 1..]
            .iter()
            .zip(&b[k + 1..])
            .fold(b[k], |s, (&x, &y)| s - x * y);
        b[k] = s / row[k];
    }
}

/// `|det|` of the square submatrix of the `rows x cols` matrix `a` made of `columns`
/// (Gaussian elimination with partial pivoting).
pub fn abs_det(a: &[f64], rows: usize, cols: usize, columns: &[usize]) -> f64 {
    let n = columns.len();
    if n != rows {
        return 0.0;
    }
    let mut b: Vec<f64> = (0..n)
        .flat_map(|i| columns.iter().map(move |&j| a[i * cols + j]))
        .collect();
    let mut det = 1.0;
    for c in 0..n {
        let p = (c..n)
            .max_by(|&i, &j| b[i * n + c].abs().total_cmp(&b[j * n + c].abs()))
            .unwrap_or(c);
        let pivot = b[p * n + c];
        if pivot == 0.0 {
            return 0.0;
        }
        if p != c {
            for j in 0..n {
                b.swap(p * n + j, c * n + j);
            }
        }
        det *= pivot;
        for i in c + 1..n {
            let f = b[i * n + c] / pivot;
            for j in c..n {
                b[i * n + j] -= f * b[c * n + j];
            }
        }
    }
    det.abs()
}

/// Like [`independent_rows_and_columns`], but the rows are taken greedily in
/// decreasing `order` (ties by index), each when it is independent of those taken.
pub fn independent_rows_in_order(
    a: &[f64],
    rows: usize,
    cols: usize,
    order: &[u32],
) -> (Vec<usize>, Vec<usize>) {
    let mut sequence: Vec<usize> = (0..rows).collect();
    sequence.sort_by_key(|&i| std::cmp::Reverse(order.get(i).copied().unwrap_or(u32::MAX)));
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let mut chosen_rows = Vec::new();
    for i in sequence {
        if basis.len() == cols {
            break;
        }
        let mut r = a[i * cols..(i + 1) * cols].to_vec();
        let norm = r.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if norm == 0.0 || !norm.is_finite() {
            continue;
        }
        for b in &basis {
            let p = b
                .iter()
                .enumerate()
                .fold(0, |k, (j, x)| if x.abs() > b[k].abs() { j } else { k });
            let f = r[p] / b[p];
            for (x, y) in r.iter_mut().zip(b) {
                *x -= f * y;
            }
        }
        if r.iter().fold(0.0f64, |m, x| m.max(x.abs())) > 1e-10 * norm {
            basis.push(r);
            chosen_rows.push(i);
        }
    }
    with_columns(a, cols, chosen_rows)
}

/// Independent equations (rows) of the `rows x cols` matrix `a` and as many unknowns
/// (columns) they determine, both by pivoting.
pub fn independent_rows_and_columns(
    a: &[f64],
    rows: usize,
    cols: usize,
) -> (Vec<usize>, Vec<usize>) {
    let mut transposed = vec![0.0; rows * cols];
    for i in 0..rows {
        for j in 0..cols {
            transposed[j * rows + i] = a[i * cols + j];
        }
    }
    with_columns(a, cols, pick_columns(&transposed, cols, rows))
}

/// The Newton step for the unknowns `cols` from the residuals `rows`: the solution of
/// `J[rows, cols] dx = -f[rows]` (`J` row-major with `ncols` columns); None when that
/// square matrix is singular or empty.
pub fn newton_step(
    jac: &[f64],
    ncols: usize,
    rows: &[usize],
    cols: &[usize],
    f: &[f64],
) -> Option<Vec<f64>> {
    let k = rows.len();
    if k == 0 || cols.len() != k {
        return None;
    }
    let mut a = vec![0.0; k * k];
    for (ii, &i) in rows.iter().enumerate() {
        for (jj, &j) in cols.iter().enumerate() {
            a[ii * k + jj] = jac[i * ncols + j];
        }
    }
    let mut b: Vec<f64> = rows.iter().map(|&i| -f[i]).collect();
    let mut perm = vec![0; k];
    lu_solve(k, &mut a, &mut b, &mut perm).then_some(b)
}

/// The chosen rows (sorted) with as many columns that make them regular, or nothing
/// when there are not as many.
fn with_columns(a: &[f64], cols: usize, mut chosen_rows: Vec<usize>) -> (Vec<usize>, Vec<usize>) {
    chosen_rows.sort_unstable();
    let sub: Vec<f64> = chosen_rows
        .iter()
        .flat_map(|&i| a[i * cols..(i + 1) * cols].iter().copied())
        .collect();
    let chosen_cols = pick_columns(&sub, chosen_rows.len(), cols);
    if chosen_cols.len() < chosen_rows.len() {
        return (Vec::new(), Vec::new());
    }
    (chosen_rows, chosen_cols)
}

/// Picks as many columns of the `rows x cols` matrix `a` as it has independent rows,
/// those that make it best conditioned (greedy Gaussian elimination with complete
/// pivoting); sorted.
pub fn pick_columns(a: &[f64], rows: usize, cols: usize) -> Vec<usize> {
    let mut a = a.to_vec();
    let mut chosen = Vec::new();
    let mut used = vec![false; cols];
    let mut used_row = vec![false; rows];
    for _ in 0..rows {
        let mut best = (0.0, usize::MAX, usize::MAX);
        for i in 0..rows {
            if used_row[i] {
                continue;
            }
            for j in 0..cols {
                if !used[j] && a[i * cols + j].abs() > best.0 {
                    best = (a[i * cols + j].abs(), i, j);
                }
            }
        }
        if best.1 == usize::MAX || best.0 < 1e-14 {
            break;
        }
        let (_, pi, pj) = best;
        used[pj] = true;
        used_row[pi] = true;
        chosen.push(pj);
        let p = a[pi * cols + pj];
        for i in 0..rows {
            if i != pi {
                let f = a[i * cols + pj] / p;
                for j in 0..cols {
                    a[i * cols + j] -= f * a[pi * cols + j];
                }
            }
        }
    }
    chosen.sort();
    chosen
}
