//! `real-traffic`'s parameters: the radar, the tracker configurations' tuning and the
//! scoring, each settable with `--set`.

use crate::params::ParamSpec;
use crate::tracker_params as tp;

/// Paris CDG's aerodrome reference point (AIP France, AD 2 LFPG: 49°00′35″ N,
/// 002°32′52″ E, 392 ft).
const CDG: (f64, f64, f64) = (49.009_722, 2.547_778, 119.0);

/// The parameters with their defaults and ranges.
pub(super) fn params() -> Vec<ParamSpec> {
    vec![
        ParamSpec::new(
            "duration",
            3600.0,
            10.0,
            3600.0,
            "tracked time from the hour's start (s)",
        ),
        ParamSpec::new(
            "radar_lat",
            CDG.0,
            -89.0,
            89.0,
            "radar latitude (deg, WGS-84)",
        ),
        ParamSpec::new("radar_lon", CDG.1, -180.0, 180.0, "radar longitude (deg)"),
        ParamSpec::new(
            "radar_alt",
            CDG.2,
            -500.0,
            9000.0,
            "radar height above the ellipsoid (m)",
        ),
        ParamSpec::new("period", 5.0, 0.5, 60.0, "revolution period (s)"),
        ParamSpec::new(
            "clockwise",
            1.0,
            0.0,
            1.0,
            "1: the beam turns clockwise (north → east), 0: counter-clockwise (a switch: ≥ 0.5 is 1)",
        ),
        ParamSpec::new(
            "north_time",
            0.0,
            -1e6,
            1e6,
            "a time at which the beam points north (s)",
        ),
        ParamSpec::new("sigma_r", 70.0, 1e-3, 1e4, "range noise σ (m)"),
        ParamSpec::new("sigma_az_deg", 0.08, 1e-6, 10.0, "azimuth noise σ (deg)"),
        ParamSpec::new("p_d", 0.9, 0.05, 1.0, "detection probability"),
        ParamSpec::new(
            "clutter",
            10.0,
            0.0,
            1e5,
            "mean false plots per revolution, uniform per m² over the coverage",
        ),
        ParamSpec::new("min_range", 500.0, 0.0, 1e5, "radar minimum range (m)"),
        ParamSpec::new("max_range", 150_000.0, 1e3, 1e6, "radar maximum range (m)"),
        tp::SECTOR_FRACTION.spec(0.125),
        tp::KF_SIGMA_A.spec(5.0),
        tp::IMM_SIGMA_LOW.spec(0.5),
        tp::IMM_SIGMA_HIGH.spec(10.0),
        tp::IMM_P_STAY
            .help("IMM probability of staying in a mode per revolution")
            .spec(0.95),
        tp::CONFIRM_M.spec(3.0),
        tp::CONFIRM_N.spec(4.0),
        tp::MAX_MISSES.spec(4.0),
        tp::MAX_SPEED.spec(350.0),
        ParamSpec::new(
            "init_revolutions",
            1.4,
            1.01,
            10.0,
            "two-point initiation: an unused plot waits this many revolutions for its pair",
        ),
        tp::AC_CV_SIGMA_LOW.spec(0.3),
        tp::AC_CV_SIGMA_HIGH.spec(2.0),
        tp::AC_CT_SIGMA_A.spec(0.5),
        tp::AC_CT_SIGMA_OMEGA_DEG.spec(0.2),
        ParamSpec::new(
            "score",
            0.0,
            0.0,
            1.0,
            "1: confirm and delete by track score (SPRT, with the clutter density), 0: M of N",
        ),
        tp::FALSE_CONFIRM.spec(1e-4),
        tp::DELETE_DROP.spec(9.0),
        tp::NEW_TARGET_DENSITY
            .help("track score: new targets per m² per revolution")
            .spec(1e-11),
        tp::JPDA_MAX_EVENTS.spec(1000.0),
        ParamSpec::new("score_step", 5.0, 0.1, 60.0, "scoring grid step (s)"),
        ParamSpec::new(
            "cutoff",
            1000.0,
            1.0,
            1e6,
            "track-to-truth assignment and GOSPA cut-off (m)",
        ),
    ]
}
