//! Trigonometric coefficients of the coordinated-turn transition, stable as the turn
//! angle `θ = ωT → 0` (private helper).
//!
//! With `θ = ωT` the turn transition contains `sin(ωT)/ω = T·S(θ)` and
//! `(1 − cos ωT)/ω = T·C(θ)`, where
//!
//! ```text
//! S(θ) = sin θ / θ          = 1 − θ²/6 + θ⁴/120 − …
//! C(θ) = (1 − cos θ) / θ    = θ/2 − θ³/24 + θ⁵/720 − …
//! ```
//!
//! Their `ω`-derivatives are `∂(T S)/∂ω = T² S'(θ)`, `∂²(T S)/∂ω² = T³ S''(θ)` (and the same
//! for `C`). For `|θ| < SERIES_LIMIT` the Taylor series (truncation error below 1e-16
//! relative) is used; above it the closed forms, written without `1 − cos θ`
//! (as `2 sin²(θ/2)`) to avoid cancellation. Both branches agree to about 1e-13 relative
//! at the switch, and at `θ = 0` the series gives the exact limits (`S = 1`, `C = 0`,
//! `S' = 0`, `C' = 1/2`, `S'' = −1/3`, `C'' = 0`), so there is never a 0/0.

/// Below this `|θ|` the series are used.
const SERIES_LIMIT: f64 = 0.1;

/// `sin θ`, `cos θ`, `S`, `C` and their first and second derivatives in `θ`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TurnCoeffs {
    /// `sin θ`.
    pub(crate) sin: f64,
    /// `cos θ`.
    pub(crate) cos: f64,
    /// `S(θ) = sin θ / θ`.
    pub(crate) s: f64,
    /// `C(θ) = (1 − cos θ) / θ`.
    pub(crate) c: f64,
    /// `S'(θ) = (θ cos θ − sin θ) / θ²`.
    pub(crate) ds: f64,
    /// `C'(θ) = (θ sin θ − (1 − cos θ)) / θ²`.
    pub(crate) dc: f64,
    /// `S''(θ) = (2 sin θ − 2θ cos θ − θ² sin θ) / θ³`.
    pub(crate) dds: f64,
    /// `C''(θ) = (θ² cos θ − 2θ sin θ + 2(1 − cos θ)) / θ³`.
    pub(crate) ddc: f64,
}

/// The coefficients at the turn angle `theta = ω T`: [`turn_sc`]'s four, and the
/// derivatives (series below [`SERIES_LIMIT`], closed forms above it).
pub(crate) fn turn_coeffs(theta: f64) -> TurnCoeffs {
    let [sin, cos, s, c] = turn_sc_direct(theta);
    if theta.abs() < SERIES_LIMIT {
        let u = theta * theta;
        // Taylor coefficients of S = Σ (−1)ᵏ θ²ᵏ/(2k+1)! and C = Σ (−1)ᵏ⁺¹ θ²ᵏ⁻¹/(2k)!,
        // differentiated term by term.
        let ds = theta
            * (-1.0 / 3.0
                + u * (1.0 / 30.0 - u * (1.0 / 840.0 - u * (1.0 / 45_360.0 - u / 3_991_680.0))));
        let dds =
            -1.0 / 3.0 + u * (1.0 / 10.0 - u * (1.0 / 168.0 - u * (1.0 / 6_480.0 - u / 443_520.0)));
        let dc = 0.5 - u * (1.0 / 8.0 - u * (1.0 / 144.0 - u * (1.0 / 5_760.0 - u / 403_200.0)));
        let ddc = theta
            * (-0.25
                + u * (1.0 / 36.0 - u * (1.0 / 960.0 - u * (1.0 / 50_400.0 - u / 4_354_560.0))));
        TurnCoeffs {
            sin,
            cos,
            s,
            c,
            ds,
            dc,
            dds,
            ddc,
        }
    } else {
        let one_minus_cos = one_minus_cos(sin, cos);
        let t2 = theta * theta;
        let t3 = t2 * theta;
        TurnCoeffs {
            sin,
            cos,
            s,
            c,
            ds: (theta * cos - sin) / t2,
            dc: (theta * sin - one_minus_cos) / t2,
            dds: (2.0 * sin - 2.0 * theta * cos - t2 * sin) / t3,
            ddc: (t2 * cos - 2.0 * theta * sin + 2.0 * one_minus_cos) / t3,
        }
    }
}

/// `1 − cos θ` without cancellation: `sin²θ / (1 + cos θ)` while `cos θ > 0`, directly
/// otherwise (then `1 − cos θ ≥ 1`).
#[inline]
fn one_minus_cos(sin: f64, cos: f64) -> f64 {
    if cos > 0.0 {
        sin * sin / (1.0 + cos)
    } else {
        1.0 - cos
    }
}

/// `(sin θ, cos θ, S(θ), C(θ))` alone, for the transition (no derivatives): the Taylor
/// series below [`SERIES_LIMIT`] (truncation below 1e-16 relative), the closed forms with
/// [`one_minus_cos`] above it.
///
/// The values at `|θ|` are kept per thread for the next call: an IMM bank predicts the
/// same turn models over the same interval many times per step (the 5 × 3 multi-IMM: ten
/// coordinated-turn predictions at `±ωT`), and the sine and cosine are most of a
/// prediction's cost. `sin` and `C` are odd and `cos` and `S` even in `θ`, so `−|θ|` is
/// served from `|θ|` with the signs flipped: the results are those of the direct
/// evaluation, bit for bit (test).
#[inline]
pub(crate) fn turn_sc(theta: f64) -> (f64, f64, f64, f64) {
    use std::cell::Cell;
    thread_local! {
        static LAST: Cell<(u64, [f64; 4])> = const { Cell::new((u64::MAX, [0.0; 4])) };
    }
    let a = theta.abs();
    let key = a.to_bits();
    // `get`/`set` on the thread-local cell, not a closure through `with`: the closure's
    // call returned the values through memory written entry by entry and read back in
    // pairs, a store-forwarding stall that cost about as much as the sine it saved.
    let (k, cached) = LAST.get();
    let [sin, cos, s, c] = if k == key {
        cached
    } else {
        let v = turn_sc_direct(a);
        LAST.set((key, v));
        v
    };
    if theta.is_sign_negative() {
        (-sin, cos, s, -c)
    } else {
        (sin, cos, s, c)
    }
}

/// [`turn_sc`] evaluated directly.
#[inline]
fn turn_sc_direct(theta: f64) -> [f64; 4] {
    let (sin, cos) = theta.sin_cos();
    if theta.abs() < SERIES_LIMIT {
        let u = theta * theta;
        let s = 1.0 - u / 6.0 * (1.0 - u / 20.0 * (1.0 - u / 42.0 * (1.0 - u / 72.0)));
        let c = theta * (0.5 - u / 24.0 * (1.0 - u / 30.0 * (1.0 - u / 56.0 * (1.0 - u / 90.0))));
        [sin, cos, s, c]
    } else {
        [sin, cos, sin / theta, one_minus_cos(sin, cos) / theta]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn light_coefficients_equal_the_full_ones() {
        // `turn_coeffs` builds on `turn_sc_direct`; the cached `turn_sc` must agree with both.
        for theta in [
            0.0, 1e-9, -0.05, 0.0999, 0.1, 0.26, -0.26, 1.0, 1.6, -2.5, 3.1, 6.0, -20.0,
        ] {
            let k = turn_coeffs(theta);
            let (sin, cos, s, c) = turn_sc(theta);
            // The cached path (a repeat, and after the mirrored angle) equals the direct one.
            let direct = turn_sc_direct(theta);
            let _ = turn_sc(-theta);
            let again = turn_sc(theta);
            for (x, y) in [sin, cos, s, c].iter().zip(&direct) {
                assert_eq!(x.to_bits(), y.to_bits(), "θ = {theta}");
            }
            assert_eq!(
                [again.0, again.1, again.2, again.3].map(f64::to_bits),
                direct.map(f64::to_bits)
            );
            assert_eq!(
                (sin.to_bits(), cos.to_bits()),
                (k.sin.to_bits(), k.cos.to_bits())
            );
            assert!(
                (s - k.s).abs() <= 1e-15 * k.s.abs().max(1e-300),
                "S({theta})"
            );
            assert!(
                (c - k.c).abs() <= 4e-15 * k.c.abs().max(1e-300),
                "C({theta}): {c} vs {}",
                k.c
            );
        }
    }

    /// Relative agreement of the two branches on both sides of the switch.
    #[test]
    fn branches_agree_at_switch() {
        let below = turn_coeffs(SERIES_LIMIT * (1.0 - 1e-12));
        let above = turn_coeffs(SERIES_LIMIT);
        let pairs = [
            (below.s, above.s),
            (below.c, above.c),
            (below.ds, above.ds),
            (below.dc, above.dc),
            (below.dds, above.dds),
            (below.ddc, above.ddc),
        ];
        for (a, b) in pairs {
            // Closed forms lose ~1e3 ulp to cancellation at θ = 0.1 (≈ 2e-13 relative).
            assert!((a - b).abs() <= 1e-12 * b.abs(), "{a} vs {b}");
        }
    }

    #[test]
    fn exact_limits_at_zero() {
        let k = turn_coeffs(0.0);
        assert!((k.s - 1.0).abs() < f64::EPSILON);
        assert!(k.c.abs() < f64::EPSILON);
        assert!(k.ds.abs() < f64::EPSILON);
        assert!((k.dc - 0.5).abs() < f64::EPSILON);
        assert!((k.dds + 1.0 / 3.0).abs() < f64::EPSILON);
        assert!(k.ddc.abs() < f64::EPSILON);
    }

    #[test]
    fn series_match_closed_forms_at_moderate_angle() {
        // At θ = 0.05 the closed forms are still accurate to ~1e-12 relative (cancellation
        // ≈ 2/θ² ulp for C''), so they check the series coefficients.
        let theta = 0.05_f64;
        let k = turn_coeffs(theta);
        let (sin, cos) = theta.sin_cos();
        let omc = 2.0 * (0.5 * theta).sin().powi(2);
        let t2 = theta * theta;
        let t3 = t2 * theta;
        let exact = [
            (k.s, sin / theta),
            (k.c, omc / theta),
            (k.ds, (theta * cos - sin) / t2),
            (k.dc, (theta * sin - omc) / t2),
            (k.dds, (2.0 * sin - 2.0 * theta * cos - t2 * sin) / t3),
            (k.ddc, (t2 * cos - 2.0 * theta * sin + 2.0 * omc) / t3),
        ];
        for (a, b) in exact {
            assert!((a - b).abs() <= 1e-11 * b.abs(), "{a} vs {b}");
        }
    }
}
