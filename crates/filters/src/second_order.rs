//! The Hessian terms of the truncated second-order filters.

use argus_core_math::{Matrix, Vector};

/// The second-order terms of a function `g: ℝᴺ → ℝᴷ` with Hessians `Gᵢ = ∂²gᵢ/∂x²`
/// at a Gaussian `N(x̂, P)`:
///
/// - mean correction `bᵢ = ½ tr(Gᵢ P)`, so `E[g(x)] ≈ g(x̂) + b`;
/// - covariance term `Cᵢⱼ = ½ tr(Gᵢ P Gⱼ P)`, so `Cov[g(x)] ≈ J P Jᵀ + C`.
///
/// Both are exact when `g` is quadratic (Gaussian third moments vanish).
///
/// # References
/// Bar-Shalom, Li & Kirubarajan (2001), *Estimation with Applications to Tracking
/// and Navigation*, §10.3.2 (eqs 10.3.2-4, 10.3.2-6, 10.3.3-2, 10.3.3-4); Gelb (1974),
/// *Applied Optimal Estimation*, Table 6.1-2; seed 001 (truncated second-order filter).
#[must_use]
#[allow(non_snake_case)]
pub fn second_order_terms<const N: usize, const K: usize>(
    hessians: &[Matrix<N, N>; K],
    P: &Matrix<N, N>,
) -> (Vector<K>, Matrix<K, K>) {
    let GP: [Matrix<N, N>; K] =
        std::array::from_fn(|i| hessians.get(i).map_or(Matrix::zeros(), |g| g * P));
    let mut mean = Vector::<K>::zeros();
    let mut cov = Matrix::<K, K>::zeros();
    for (i, gi) in GP.iter().enumerate() {
        mean[i] = 0.5 * gi.trace();
        for (j, gj) in GP.iter().enumerate().take(i + 1) {
            // tr(A B) = Σₐ Σ_b A[a,b] B[b,a].
            let t = 0.5 * gi.component_mul(&gj.transpose()).sum();
            cov[(i, j)] = t;
            cov[(j, i)] = t;
        }
    }
    (mean, cov)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_form_moments() {
        // g(x) = xᵀ A x with symmetric A: Hessian 2A, E[g] = x̂ᵀAx̂ + tr(AP),
        // Var[g] = 4 x̂ᵀAPAx̂ + 2 tr(APAP) (Gaussian moments of a quadratic form).
        let a = Matrix::<2, 2>::new(1.0, 0.3, 0.3, -0.5);
        let p = Matrix::<2, 2>::new(2.0, 0.4, 0.4, 1.0);
        let (b, c) = second_order_terms(&[a * 2.0], &p);
        assert!((b[0] - (a * p).trace()).abs() < 1e-14);
        assert!((c[(0, 0)] - 2.0 * (a * p * a * p).trace()).abs() < 1e-13);
    }
}
