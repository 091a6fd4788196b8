//! Gauss–Legendre quadrature for the performance-prediction integrals.

/// Nodes and weights of the `K`-point Gauss–Legendre rule on `[−1, 1]` (Newton's
/// iteration on `P_K` from Chebyshev starting points; Golub–Welsch-free, no allocation).
pub(crate) fn gauss_legendre<const K: usize>() -> ([f64; K], [f64; K]) {
    let mut x = [0.0; K];
    let mut w = [0.0; K];
    let k = K as f64;
    for i in 0..K {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (k + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for j in 2..=K {
                let jf = j as f64;
                let p2 = ((2.0 * jf - 1.0) * z * p1 - (jf - 1.0) * p0) / jf;
                p0 = p1;
                p1 = p2;
            }
            let pk = if K == 1 { z } else { p1 };
            let pkm1 = if K == 1 { 1.0 } else { p0 };
            dp = k * (z * pk - pkm1) / (z * z - 1.0);
            let dz = pk / dp;
            z -= dz;
            if dz.abs() < 1e-15 {
                break;
            }
        }
        x[i] = z;
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
    (x, w)
}

/// `∫_a^b f` by composite Gauss–Legendre (16 points on each of `panels` panels).
pub(crate) fn integrate<F: FnMut(f64) -> f64>(a: f64, b: f64, panels: usize, mut f: F) -> f64 {
    let (x, w) = gauss_legendre::<16>();
    let h = (b - a) / panels as f64;
    let mut sum = 0.0;
    for p in 0..panels {
        let lo = a + p as f64 * h;
        let mid = lo + 0.5 * h;
        for (xi, wi) in x.iter().zip(w.iter()) {
            sum += wi * f(mid + 0.5 * h * xi);
        }
    }
    sum * 0.5 * h
}

/// `Γ(n/2)` for a positive integer `n` (`Γ(1/2) = √π`, `Γ(1) = 1`, `Γ(s+1) = sΓ(s)`).
pub(crate) fn gamma_half(n: usize) -> f64 {
    let (mut s, mut g) = if n.is_multiple_of(2) {
        (1.0, 1.0)
    } else {
        (0.5, std::f64::consts::PI.sqrt())
    };
    while s < n as f64 / 2.0 - 1e-9 {
        g *= s;
        s += 1.0;
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rule_is_exact_for_polynomials() {
        // A 16-point rule integrates degree ≤ 31 exactly: ∫_0^2 x^31 = 2^32/32.
        let v = integrate(0.0, 2.0, 1, |x| x.powi(31));
        assert!((v / (2f64.powi(32) / 32.0) - 1.0).abs() < 1e-12);
        let (_, w) = gauss_legendre::<16>();
        assert!((w.iter().sum::<f64>() - 2.0).abs() < 1e-13);
        // ∫_0^π sin = 2.
        assert!((integrate(0.0, std::f64::consts::PI, 4, f64::sin) - 2.0).abs() < 1e-13);
    }

    #[test]
    fn gamma_half_values() {
        // Γ(1/2)=√π, Γ(1)=1, Γ(3/2)=√π/2, Γ(2)=1, Γ(5/2)=3√π/4, Γ(3)=2.
        let sp = std::f64::consts::PI.sqrt();
        let expect = [sp, 1.0, sp / 2.0, 1.0, 0.75 * sp, 2.0];
        for (n, e) in (1..=6).zip(expect) {
            assert!((gamma_half(n) - e).abs() < 1e-14, "n = {n}");
        }
    }
}
