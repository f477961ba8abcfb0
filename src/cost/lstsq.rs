//! A small least-squares solver for the cost model's fit (at most a dozen unknowns, a few
//! dozen samples): Householder QR, non-negative least squares (Lawson and Hanson's active set
//! method, "Solving Least Squares Problems", 1974, ch. 23) and the unscaled covariance
//! `(AᵀA)⁻¹`. No linear-algebra crate: the sizes are tiny and the normal equations are
//! avoided, QR works on `A` itself.
//!
//! Matrices are given as columns (`columns[j][i]` is row `i` of column `j`).

/// A column whose remaining norm after orthogonalisation against the columns before it is
/// below this fraction of its own norm is taken as a combination of them (rank deficient).
/// The fit scales every column to unit norm first, so this is a bound on the sine of the
/// angle between the column and the span of the others: 1e-9 is far above rounding
/// (1e-16 x a few dozen rows) and far below any design a calibration would want to keep.
const DEPENDENT: f64 = 1e-9;

/// The QR factorisation of a set of columns, and the least-squares solution with it.
pub(super) struct Qr {
    /// Upper triangular `R` (`k x k`, row-major: `r[i][j]`).
    r: Vec<Vec<f64>>,
    /// The least-squares solution.
    pub(super) x: Vec<f64>,
}

/// Least squares `min |A x − b|` over the given columns. `Err(j)`: column `j` (index into
/// `columns`) is zero or a linear combination of the columns before it, or there are fewer
/// rows than columns.
pub(super) fn qr_solve(columns: &[&[f64]], b: &[f64]) -> Result<Qr, usize> {
    let k = columns.len();
    let m = b.len();
    let mut a: Vec<Vec<f64>> = columns.iter().map(|c| c.to_vec()).collect();
    let mut y = b.to_vec();
    for j in 0..k {
        if j >= m || a[j].len() != m {
            return Err(j);
        }
        let original = norm(columns[j]);
        let rest = norm(&a[j][j..]);
        if original == 0.0 || rest <= DEPENDENT * original {
            return Err(j);
        }
        let alpha = if a[j][j] > 0.0 { -rest } else { rest };
        let mut v: Vec<f64> = a[j][j..].to_vec();
        v[0] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        if vv > 0.0 {
            let reflect = |c: &mut [f64]| {
                let d: f64 = v.iter().zip(c.iter()).map(|(p, q)| p * q).sum();
                let f = 2.0 * d / vv;
                for (ci, vi) in c.iter_mut().zip(&v) {
                    *ci -= f * vi;
                }
            };
            for col in a.iter_mut().skip(j) {
                reflect(&mut col[j..]);
            }
            reflect(&mut y[j..]);
        }
    }
    let r: Vec<Vec<f64>> = (0..k)
        .map(|i| (0..k).map(|j| if j >= i { a[j][i] } else { 0.0 }).collect())
        .collect();
    let x = back_substitute(&r, &y[..k]);
    Ok(Qr { r, x })
}

impl Qr {
    /// `(AᵀA)⁻¹ = R⁻¹ R⁻ᵀ`: the covariance of the solution per unit residual variance.
    pub(super) fn inverse_gram(&self) -> Vec<Vec<f64>> {
        let k = self.r.len();
        // Columns of R⁻¹: R x = e_j.
        let inv: Vec<Vec<f64>> = (0..k)
            .map(|j| {
                let e: Vec<f64> = (0..k).map(|i| f64::from(u8::from(i == j))).collect();
                back_substitute(&self.r, &e)
            })
            .collect();
        // (R⁻¹ R⁻ᵀ)[a][b] = Σ_j R⁻¹[a][j] R⁻¹[b][j]; inv[j][a] = R⁻¹[a][j].
        (0..k)
            .map(|a| {
                (0..k)
                    .map(|b| (0..k).map(|j| inv[j][a] * inv[j][b]).sum())
                    .collect()
            })
            .collect()
    }
}

/// Solves `R x = y` for upper triangular `R` with a non-zero diagonal.
fn back_substitute(r: &[Vec<f64>], y: &[f64]) -> Vec<f64> {
    let k = r.len();
    let mut x = vec![0.0; k];
    for i in (0..k).rev() {
        let s: f64 = (i + 1..k).map(|j| r[i][j] * x[j]).sum();
        x[i] = (y[i] - s) / r[i][i];
    }
    x
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// `A x`.
pub(super) fn apply(columns: &[Vec<f64>], x: &[f64]) -> Vec<f64> {
    let m = columns.first().map_or(0, Vec::len);
    (0..m)
        .map(|i| columns.iter().zip(x).map(|(c, xj)| c[i] * xj).sum())
        .collect()
}

/// Non-negative least squares `min |A x − b|, x ≥ 0` (Lawson and Hanson). The columns must
/// be linearly independent (check with [`qr_solve`] on all of them first); `None` if the
/// iteration does not settle (it does in at most a few times the number of columns steps
/// for such a design).
pub(super) fn nnls(columns: &[Vec<f64>], b: &[f64]) -> Option<Vec<f64>> {
    let n = columns.len();
    let mut x = vec![0.0; n];
    let mut passive = vec![false; n];
    // A column that entered and came back non-positive at once: skipped until x changes.
    let mut blocked = vec![false; n];
    let gradient = |x: &[f64]| -> Vec<f64> {
        let ax = apply(columns, x);
        let res: Vec<f64> = b.iter().zip(&ax).map(|(p, q)| p - q).collect();
        columns
            .iter()
            .map(|c| c.iter().zip(&res).map(|(p, q)| p * q).sum())
            .collect()
    };
    // Gradients below this are zero: rounding of Aᵀb's largest entry, with a wide margin.
    let tolerance = 1e-12
        * columns
            .iter()
            .map(|c| c.iter().zip(b).map(|(p, q)| p * q).sum::<f64>().abs())
            .fold(1.0, f64::max);
    let solve_passive = |passive: &[bool]| -> Option<Vec<f64>> {
        let idx: Vec<usize> = (0..n).filter(|&j| passive[j]).collect();
        let cols: Vec<&[f64]> = idx.iter().map(|&j| columns[j].as_slice()).collect();
        let qr = qr_solve(&cols, b).ok()?;
        let mut z = vec![0.0; n];
        for (&j, v) in idx.iter().zip(qr.x) {
            z[j] = v;
        }
        Some(z)
    };
    for _ in 0..(10 * n + 10) {
        let w = gradient(&x);
        let candidate = (0..n)
            .filter(|&j| !passive[j] && !blocked[j] && w[j] > tolerance)
            .max_by(|&a, &c| w[a].total_cmp(&w[c]));
        let Some(t) = candidate else {
            return Some(x);
        };
        passive[t] = true;
        let mut first = true;
        loop {
            let z = solve_passive(&passive)?;
            if (0..n).all(|j| !passive[j] || z[j] > 0.0) {
                x = z;
                blocked.iter_mut().for_each(|b| *b = false);
                break;
            }
            if first && z[t] <= 0.0 {
                passive[t] = false;
                blocked[t] = true;
                break;
            }
            first = false;
            // Step from x towards z as far as every passive variable stays non-negative.
            let alpha = (0..n)
                .filter(|&j| passive[j] && z[j] <= 0.0)
                .map(|j| x[j] / (x[j] - z[j]))
                .fold(1.0, f64::min);
            for j in 0..n {
                x[j] += alpha * (z[j] - x[j]);
                if passive[j] && x[j] <= 1e-15 * x.iter().fold(1.0, |m, v| f64::max(m, v.abs())) {
                    passive[j] = false;
                    x[j] = 0.0;
                }
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cols(rows: &[&[f64]]) -> Vec<Vec<f64>> {
        let n = rows[0].len();
        (0..n)
            .map(|j| rows.iter().map(|r| r[j]).collect())
            .collect()
    }

    #[test]
    fn qr_solves_an_overdetermined_system_exactly_when_consistent() {
        let a = cols(&[&[1.0, 0.0], &[1.0, 1.0], &[1.0, 2.0], &[1.0, 3.0]]);
        let b = [1.0, 3.0, 5.0, 7.0]; // 1 + 2 t
        let refs: Vec<&[f64]> = a.iter().map(Vec::as_slice).collect();
        let qr = qr_solve(&refs, &b).unwrap();
        // Rounding only: the system is consistent and well conditioned.
        assert!(
            (qr.x[0] - 1.0).abs() < 1e-12 && (qr.x[1] - 2.0).abs() < 1e-12,
            "{:?}",
            qr.x
        );
        // (AᵀA)⁻¹ for t = 0..3: AᵀA = [[4, 6], [6, 14]], determinant 20.
        let c = qr.inverse_gram();
        let expected = [[14.0 / 20.0, -6.0 / 20.0], [-6.0 / 20.0, 4.0 / 20.0]];
        for i in 0..2 {
            for j in 0..2 {
                assert!((c[i][j] - expected[i][j]).abs() < 1e-12, "{c:?}");
            }
        }
    }

    #[test]
    fn dependent_and_zero_columns_are_named() {
        let a = cols(&[&[1.0, 2.0, 0.0], &[2.0, 4.0, 0.0], &[3.0, 6.0, 0.0]]);
        let refs: Vec<&[f64]> = a.iter().map(Vec::as_slice).collect();
        assert_eq!(qr_solve(&refs, &[1.0, 2.0, 3.0]).err(), Some(1));
        assert_eq!(
            qr_solve(&[refs[0], refs[2]], &[1.0, 2.0, 3.0]).err(),
            Some(1)
        );
        // Fewer rows than columns.
        let wide = cols(&[&[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0]]);
        let refs: Vec<&[f64]> = wide.iter().map(Vec::as_slice).collect();
        assert_eq!(qr_solve(&refs, &[1.0, 1.0]).err(), Some(2));
    }

    #[test]
    fn nnls_pins_a_negative_coefficient_at_zero() {
        // b = 2 a0 − 1 a1 exactly: unconstrained gives (2, −1); with x ≥ 0 the best is a
        // multiple of a0 alone.
        let a = cols(&[&[1.0, 0.0], &[1.0, 1.0], &[1.0, 2.0]]);
        let b: Vec<f64> = (0..3).map(|t| 2.0 - f64::from(t)).collect();
        let x = nnls(&a, &b).unwrap();
        assert_eq!(x[1], 0.0);
        // min |x0 (1,1,1) − (2,1,0)|: x0 = mean = 1.
        assert!((x[0] - 1.0).abs() < 1e-12, "{x:?}");
        // A consistent non-negative system is solved exactly.
        let b: Vec<f64> = (0..3).map(|t| 2.0 + 0.5 * f64::from(t)).collect();
        let x = nnls(&a, &b).unwrap();
        assert!(
            (x[0] - 2.0).abs() < 1e-12 && (x[1] - 0.5).abs() < 1e-12,
            "{x:?}"
        );
    }
}
