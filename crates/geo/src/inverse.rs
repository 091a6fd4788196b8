//! ECEF → geodetic: the latitude as the root of one smooth scalar equation,
//! solved by safeguarded Newton iteration to round-off everywhere.
//!
//! With `R = √(X² + Y²)` and `Z ≥ 0` (the southern hemisphere by symmetry), the foot
//! of the normal through the point has latitude `φ ∈ [0, π/2]` solving
//!
//! `g(φ) = R sin φ − Z cos φ − e² N(φ) sin φ cos φ = 0`,  `N = a / √(1 − e² sin²φ)`,
//!
//! (from `R = (N + h) cos φ`, `Z = (N (1 − e²) + h) sin φ`, eliminating `h`), and then
//!
//! `h = R cos φ + Z sin φ − a √(1 − e² sin²φ)`,
//!
//! which holds at every latitude (no division by `cos φ` near the poles). `g(0) = −Z ≤ 0`
//! and `g(π/2) = R ≥ 0` bracket a root; outside the ellipsoid's evolute (an astroid
//! reaching `a e² ≈ 42.7 km` from the centre for WGS-84, so everywhere a radar or an
//! aircraft can be) the root is unique and Newton's method from the surface solution
//! `tan φ₀ = Z / ((1 − e²) R)` converges in 2–4 steps, with bisection as the fallback
//! whenever a step would leave the bracket. Inside the evolute up to three roots
//! share the quadrant; each is bracketed on a grid and refined, and the one nearest
//! the surface (largest `h`) is returned, the choice GeographicLib's `Geocentric`
//! makes (Karney 2011, Appendix B).
//!
//! # References
//! Karney (2011), *Geodesics on an ellipsoid of revolution*, arXiv:1102.1215,
//! Appendix B (the evolute and the nearest-surface choice); Bowring (1976), *Survey
//! Review* 23(181) (the parametric form of the foot point).

use std::f64::consts::FRAC_PI_2;

use crate::ellipsoid::Ellipsoid;
use crate::error::{GeoError, finite};
use crate::geodetic::{Ecef, Geodetic, wrap_pi};

/// Grid points used to bracket the roots inside the evolute.
const EVOLUTE_GRID: usize = 256;
/// Newton/bisection stops once a step is below this many radians (≈ 6 nm on the
/// surface); the iteration then sits at round-off.
const STEP_TOL: f64 = 1e-15;
/// More than bisection needs to shrink `[0, π/2]` to `STEP_TOL` (51 halvings).
const MAX_ITER: usize = 100;

impl Ecef {
    /// The geodetic coordinates of this point on `ellipsoid` (see the module docs for
    /// the method). At the poles (`X = Y = 0`) the longitude is 0; at the centre the
    /// latitude is ±90° and `h = −b` (GeographicLib's convention).
    ///
    /// # Errors
    /// [`GeoError::NonFinite`] for a non-finite coordinate.
    pub fn to_geodetic(&self, ellipsoid: &Ellipsoid) -> Result<Geodetic, GeoError> {
        let x = finite(self.x, "ECEF x")?;
        let y = finite(self.y, "ECEF y")?;
        let z = finite(self.z, "ECEF z")?;
        let r = x.hypot(y);
        let za = z.abs();
        let lon = if r == 0.0 { 0.0 } else { wrap_pi(y.atan2(x)) };
        let phi = if inside_evolute(ellipsoid, r, za) {
            nearest_root(ellipsoid, r, za)
        } else {
            let start = za.atan2((1.0 - ellipsoid.e2()) * r);
            solve(ellipsoid, r, za, 0.0, FRAC_PI_2, start)
        };
        let h = height(ellipsoid, r, za, phi);
        let lat = if z < 0.0 { -phi } else { phi };
        Ok(Geodetic::new_unchecked(lat, lon, h))
    }
}

/// `g(φ)` and `g′(φ)` of the module docs.
fn g_and_slope(ell: &Ellipsoid, r: f64, z: f64, phi: f64) -> (f64, f64) {
    let (s, c) = phi.sin_cos();
    let (a, e2) = (ell.a(), ell.e2());
    let w = ell.w(s);
    let g = r * s - z * c - a * e2 * s * c / w;
    // d/dφ (sin φ cos φ / w) = (cos²φ − sin²φ + e² sin⁴φ) / w³.
    let dg = r * c + z * s - a * e2 * (c * c - s * s + e2 * s.powi(4)) / (w * w * w);
    (g, dg)
}

/// `h = R cos φ + Z sin φ − a w(φ)`.
fn height(ell: &Ellipsoid, r: f64, z: f64, phi: f64) -> f64 {
    let (s, c) = phi.sin_cos();
    r * c + z * s - ell.a() * ell.w(s)
}

/// Whether `(R, Z)` (`Z ≥ 0`) lies strictly inside the evolute
/// `(R / (a e²))^(2/3) + (b Z / (a² e²))^(2/3) = 1`.
fn inside_evolute(ell: &Ellipsoid, r: f64, z: f64) -> bool {
    let e2 = ell.e2();
    if e2 == 0.0 {
        // A sphere's evolute is its centre, where every latitude is a root.
        return r == 0.0 && z == 0.0;
    }
    let a = ell.a();
    (r / (a * e2)).cbrt().powi(2) + (ell.b() * z / (a * a * e2)).cbrt().powi(2) < 1.0
}

/// The root of `g` in `[lo, hi]`, where `g(lo)` and `g(hi)` differ in sign (or one is
/// zero): Newton from `start`, bisecting whenever a step leaves the bracket.
fn solve(ell: &Ellipsoid, r: f64, z: f64, lo: f64, hi: f64, start: f64) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    let lo_sign = g_and_slope(ell, r, z, lo).0 < 0.0;
    let mut phi = start.clamp(lo, hi);
    for _ in 0..MAX_ITER {
        let (g, dg) = g_and_slope(ell, r, z, phi);
        if g == 0.0 {
            return phi;
        }
        if (g < 0.0) == lo_sign {
            lo = phi;
        } else {
            hi = phi;
        }
        let newton = phi - g / dg;
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - phi).abs() <= STEP_TOL {
            return next;
        }
        phi = next;
    }
    phi
}

/// Inside the evolute: every root of `g` on `[0, π/2]` bracketed on a grid and
/// refined; the one with the largest `h` (the nearest surface point).
fn nearest_root(ell: &Ellipsoid, r: f64, z: f64) -> f64 {
    let step = FRAC_PI_2 / EVOLUTE_GRID as f64;
    let node = |i: usize| {
        if i == EVOLUTE_GRID {
            FRAC_PI_2
        } else {
            i as f64 * step
        }
    };
    let mut best: Option<(f64, f64)> = None;
    let mut consider = |phi: f64| {
        let h = height(ell, r, z, phi);
        if best.is_none_or(|(bh, _)| h > bh) {
            best = Some((h, phi));
        }
    };
    // The end points are roots exactly when g(0) = −Z or g(π/2) = R vanishes (at
    // π/2 the computed g is off by the rounding of cos(π/2), so test R itself).
    if z == 0.0 {
        consider(0.0);
    }
    if r == 0.0 {
        consider(FRAC_PI_2);
    }
    let mut prev = g_and_slope(ell, r, z, 0.0).0;
    for i in 1..EVOLUTE_GRID {
        let (a, b) = (node(i - 1), node(i));
        let cur = g_and_slope(ell, r, z, b).0;
        if cur == 0.0 {
            consider(b);
        } else if prev != 0.0 && (prev < 0.0) != (cur < 0.0) {
            consider(solve(ell, r, z, a, b, 0.5 * (a + b)));
        }
        prev = cur;
    }
    let (a, b) = (node(EVOLUTE_GRID - 1), FRAC_PI_2);
    if r > 0.0 && prev < 0.0 {
        consider(solve(ell, r, z, a, b, 0.5 * (a + b)));
    }
    // g(0) = −Z ≤ 0 ≤ R = g(π/2), so a root was considered; π/2 is only a fallback.
    best.map_or(FRAC_PI_2, |(_, phi)| phi)
}
