//! Seeded value stability of the bias-32 simulation: one 20 s run (seed 7) gives the same
//! numbers as before registration took its polar radar, bias model, bias regressor and
//! linearised conversion from `argus-sensors` (issue 6, item 3: "results unchanged").
//!
//! The reference values were printed by the previous implementation (registration's own
//! `PolarSensor::{biased_plot, bias_jacobian, converted_noise}`, commit ecc23ba). The
//! formulas are the same; only round-off may differ (`wrap_angle` of the biased azimuth,
//! `sin_cos` instead of separate `sin`/`cos`), so the tolerance is 1e-9 relative.

#![allow(clippy::unwrap_used)] // test code: a failure should panic with its message

use argus_registration::simulation::{ScenarioConfig, run};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

fn close(what: &str, got: f64, want: f64) {
    assert!(
        (got - want).abs() <= 1e-9 * want.abs(),
        "{what}: {got} vs {want} before"
    );
}

#[test]
fn bias32_run_is_unchanged_by_the_sensors_refactor() {
    let mut cfg = ScenarioConfig::bias32().unwrap();
    cfg.duration = 20.0;
    // The schedule these values were printed with: sensor 1's first plot at t = 0 (since
    // issue 17 the scenario's first plot is at 1 s; this test pins the arithmetic).
    cfg.sensors[0].offset = 0.0;
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let rec = run(&cfg, &mut || StandardNormal.sample(&mut rng)).unwrap();
    let p = rec.proposed_sq.last().unwrap();
    let want_p = [
        0.248_556_129_496_545_04,
        5.870_188_017_151_769e-8,
        2.254_042_599_289_878e-9,
        1.622_288_376_351_056e-8,
    ];
    let e = rec.exx_sq.last().unwrap();
    let want_e = [
        40.682_058_688_483_636,
        2.829_427_241_343_648e-6,
        1.417_600_837_040_398e-8,
        4.421_891_028_784_141e-7,
    ];
    for k in 0..4 {
        close("proposed squared error", p[k], want_p[k]);
        close("EXX squared error", e[k], want_e[k]);
    }
    close(
        "proposed NEES",
        *rec.proposed_nees.last().unwrap(),
        6.406_617_913_992_012,
    );
    close(
        "EXX NEES",
        *rec.exx_nees.last().unwrap(),
        7.890_358_694_292_205,
    );
    let t = &rec.tracks[1];
    close(
        "track 32 biased position",
        *t.pos_biased.last().unwrap(),
        7_121.665_916_032_811,
    );
    close(
        "track 32 compensated position",
        *t.pos_compensated.last().unwrap(),
        107.679_284_351_988_07,
    );
    close(
        "track 32 compensated velocity",
        *t.vel_compensated.last().unwrap(),
        5.421_709_711_815_852,
    );
}
