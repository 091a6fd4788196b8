//! Tests of the pipeline from the configuration's text: what each key becomes, and that
//! every bad value names its file:line: field.

use argus_tracker::{AssociationConfig, EstimatorConfig, SensorId, TrackerConfig};

use crate::error::ConfigError;
use crate::job::{Job, load};
use argus_tracker::single::{EstimatorSpec, MultiSpec};

use crate::spec::Sensor;
use crate::tracker_config::{DEFAULT_MAX_EXACT_EVENTS, MultiTarget};

/// Loads a configuration written to a temporary file `f.toml` (for the tests of this
/// module tree).
fn load_text(text: &str) -> Result<Job, ConfigError> {
    let dir = tempfile::tempdir().map_err(|e| ConfigError::Io {
        path: "tmp".into(),
        source: e,
    })?;
    let p = dir.path().join("f.toml");
    std::fs::write(&p, text).map_err(|e| ConfigError::Io {
        path: p.clone(),
        source: e,
    })?;
    load(&p).map(|l| l.job)
}

/// The line and field of an input error (a test failure for any other error).
fn at(e: &ConfigError) -> (Option<u64>, Option<String>) {
    match e {
        ConfigError::Input { at, .. } => (at.line, at.field.clone()),
        other => (None, Some(format!("not an input error: {other}"))),
    }
}

mod single {
    use super::*;

    const GOOD: &str = "[[sensor]]\nid = 3\nposition = [1.0, 2.0, 3.0]\nsigma_range = 10.0\nsigma_azimuth_deg = 0.5\nsigma_elevation_deg = 0.25\n\n[estimator]\nkind = \"ekf\"\nsigma_a = 2.0\n";

    fn single(text: &str) -> (Vec<Sensor>, EstimatorSpec) {
        match load_text(text) {
            Ok(Job::Single { sensors, estimator }) => (sensors, estimator),
            other => panic!("not a single-target job: {other:?}"),
        }
    }

    #[test]
    fn good_config_is_typed() {
        let (s, e) = single(GOOD);
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].id, 3);
        // Parsed exactly: compare bits.
        assert_eq!(
            s[0].position.map(f64::to_bits),
            [1.0f64, 2.0, 3.0].map(f64::to_bits)
        );
        let (sr, sa) = s[0].polar.unwrap();
        assert!((sr - 10.0).abs() < 1e-15);
        // 0.5° and 0.25° in radians: π/360 and π/720 (round-off).
        assert!((sa - std::f64::consts::PI / 360.0).abs() < 1e-15);
        assert!((s[0].sigma_elevation.unwrap() - std::f64::consts::PI / 720.0).abs() < 1e-15);
        assert!(matches!(e, EstimatorSpec::Ekf(v) if (v - 2.0).abs() < 1e-15));
        // A 2-D position gets z = 0.
        let (s, _) = single(&GOOD.replace("[1.0, 2.0, 3.0]", "[1.0, 2.0]"));
        assert_eq!(
            s[0].position.map(f64::to_bits),
            [1.0f64, 2.0, 0.0].map(f64::to_bits)
        );
    }

    #[test]
    fn multi_imm_defaults_are_written_once() {
        let text = "[estimator]\nkind = \"multi-imm\"\nmodels = [{ kind = \"cv\", sigma_a = 0.1 }]\nmarkov = [[1.0]]\n";
        let (_, e) = single(text);
        let EstimatorSpec::MultiImm(imm, multi) = e else {
            panic!("not a multi-IMM: {e:?}");
        };
        assert_eq!(multi, MultiSpec::DEFAULT);
        // One model: μ₀ = [1] exactly.
        assert_eq!(imm.initial, vec![1.0]);
    }

    /// A bad value, the line and field the error must name (`None`: no line), and a
    /// piece of its message.
    type Case<'a> = (&'a str, Option<u64>, Option<&'a str>, &'a str);

    fn check(cases: &[Case<'_>]) {
        for (text, line, field, msg) in cases {
            let e = load_text(text).unwrap_err();
            assert_eq!(at(&e), (*line, field.map(str::to_owned)), "{text}\n→ {e}");
            assert!(e.to_string().contains(msg), "{text}\n→ {e}");
        }
    }

    #[test]
    fn bad_sensors_and_estimators_name_their_line() {
        let imm = |models: &str, markov: &str, more: &str| {
            format!("[estimator]\nkind = \"imm\"\nmodels = [{models}]\nmarkov = {markov}\n{more}")
        };
        let cv = "{ kind = \"cv\", sigma_a = 0.1 }";
        let ct = "{ kind = \"ct\", sigma_a = 0.5, rate_deg = 3.0 }";
        let two = format!("{cv}, {ct}");
        let m2 = "[[0.9, 0.1], [0.1, 0.9]]";
        let multi = |more: &str| imm(cv, "[[1.0]]", more).replace("\"imm\"", "\"multi-imm\"");
        let twice = format!("{}\n{}", &GOOD[..GOOD.find("[estimator]").unwrap()], GOOD);
        check(&[
            (
                &GOOD.replace("[1.0, 2.0, 3.0]", "[1.0, 2.0, 3.0, 4.0]"),
                Some(3),
                Some("position"),
                "2 or 3 coordinates",
            ),
            (
                &GOOD.replace("[1.0, 2.0, 3.0]", "[nan, 2.0]"),
                Some(3),
                Some("position"),
                "must be finite",
            ),
            (
                &GOOD.replace("10.0", "-10.0"),
                Some(4),
                Some("sigma_range"),
                "non-negative",
            ),
            (
                &GOOD.replace("0.5\n", "-0.5\n"),
                Some(5),
                Some("sigma_azimuth_deg"),
                "non-negative",
            ),
            (
                &GOOD.replace("0.25", "-0.25"),
                Some(6),
                Some("sigma_elevation_deg"),
                "non-negative",
            ),
            (
                &GOOD.replace("sigma_a = 2.0", "sigma_a = -2.0"),
                Some(10),
                Some("sigma_a"),
                "non-negative",
            ),
            (
                &GOOD.replace("sigma_a = 2.0\n", ""),
                None,
                Some("sigma_a"),
                "required by estimator kind Ekf",
            ),
            (
                &GOOD.replace("\"ekf\"", "\"ukf\""),
                Some(9),
                None,
                "unknown variant `ukf`",
            ),
            (
                &GOOD.replace("id = 3", "id = -3"),
                Some(2),
                None,
                "expected u32",
            ),
            (
                &GOOD.replace("sigma_a = 2.0", "sigma_a = 2.0\nbogus = 1"),
                Some(11),
                None,
                "unknown field `bogus`",
            ),
            (
                &format!("{GOOD}[extra]\n"),
                Some(11),
                None,
                "unknown field `extra`",
            ),
            (&twice, None, Some("id"), "sensor id 3 given twice"),
            (
                &imm(cv, m2, "").replace("models = [{ kind = \"cv\", sigma_a = 0.1 }]\n", ""),
                None,
                Some("models"),
                "required by estimator kind Imm",
            ),
            (
                &imm("", "[[1.0]]", ""),
                None,
                Some("models"),
                "1 to 5 models, not 0",
            ),
            (
                &imm(&[cv; 6].join(", "), "[[1.0]]", ""),
                None,
                Some("models"),
                "not 6",
            ),
            (
                &imm("{ kind = \"ct\", sigma_a = 0.5 }", "[[1.0]]", ""),
                None,
                Some("rate_deg"),
                "required",
            ),
            (
                &imm(
                    "{ kind = \"cv\", sigma_a = 0.5, rate_deg = 1.0 }",
                    "[[1.0]]",
                    "",
                ),
                Some(3),
                Some("rate_deg"),
                "no turn rate",
            ),
            (
                &imm(
                    "{ kind = \"ct\", sigma_a = 0.5, rate_deg = 0.0 }",
                    "[[1.0]]",
                    "",
                ),
                Some(3),
                Some("rate_deg"),
                "non-zero",
            ),
            (
                &imm("{ kind = \"cv\", sigma_a = -0.5 }", "[[1.0]]", ""),
                Some(3),
                Some("sigma_a"),
                "non-negative",
            ),
            (
                &imm(&two, m2, "").replace(&format!("markov = {m2}\n"), ""),
                None,
                Some("markov"),
                "required",
            ),
            (
                &imm(&two, "[[1.0]]", ""),
                Some(4),
                Some("markov"),
                "must be 2 × 2",
            ),
            (
                &imm(&two, "[[0.9, 0.1], [0.1, 0.8]]", ""),
                Some(4),
                Some("markov"),
                "row 2 is not stochastic",
            ),
            (
                &imm(&two, "[[1.1, -0.1], [0.1, 0.9]]", ""),
                Some(4),
                Some("markov"),
                "row 1",
            ),
            (
                &imm(&two, m2, "initial = [0.2, 0.2]\n"),
                Some(5),
                Some("initial"),
                "sum = 0.4",
            ),
            (
                &imm(&two, m2, "initial = [1.0]\n"),
                Some(5),
                Some("initial"),
                "needs 2 probabilities",
            ),
            (&multi("n = 4\n"), Some(5), Some("n"), "one of [3, 5, 7, 9]"),
            (
                &multi("n = 7\nper_axis = true\n"),
                Some(5),
                Some("n"),
                "one of [3, 5] with per_axis = true",
            ),
            (
                &multi("per_axis = 1\n"),
                Some(5),
                None,
                "expected a boolean",
            ),
            (&multi("p = 0.6\n"), Some(5), Some("p"), "(n = 5)"),
            (&multi("n = 9\np = 0.3\n"), Some(6), Some("p"), "(n = 9)"),
            (
                &multi("clip = 1.0\n"),
                Some(5),
                Some("clip"),
                "must be in [0, 1)",
            ),
        ]);
    }

    #[test]
    fn a_tracker_table_makes_the_multi_target_job() {
        assert!(matches!(load_text(GOOD), Ok(Job::Single { .. })));
        assert!(matches!(
            load_text(&format!("{GOOD}[tracker]\n")),
            Ok(Job::Multi(_))
        ));
    }
}

mod tracker_checks {
    use super::*;

    /// One polar radar (lines 1–5), a KF (lines 7–9), `[tracker]` at line 11.
    const HEAD: &str = "[[sensor]]\nid = 1\nposition = [0.0, 0.0]\nsigma_range = 50.0\nsigma_azimuth_deg = 0.06\n\n[estimator]\nkind = \"kf-converted\"\nsigma_a = 2.0\n\n[tracker]\n";
    const SCORE: &str = "[tracker.score]\np_detection = 0.9\nclutter_density = 1e-9\nnew_target_density = 1e-10\nfalse_confirm = 0.01\nmissed_confirm = 0.1\ndelete_drop = 5.0\n";
    const JPDA: &str = "association = \"jpda\"\np_detection = 0.9\nclutter_density = 1e-9\n";

    /// Asserts that `tracker` (after [`HEAD`]) fails at `line`, `field`, with `msg`.
    fn fails(tracker: &str, line: u64, field: &str, msg: &str) {
        let text = format!("{HEAD}{tracker}");
        let e = load_text(&text).unwrap_err();
        assert_eq!(
            at(&e),
            (Some(line), Some(field.to_owned())),
            "{text}\n→ {e}"
        );
        assert!(e.to_string().contains(msg), "{text}\n→ {e}");
    }

    #[test]
    fn every_tracker_check_names_its_key() {
        let positive = "must be finite and positive";
        fails(
            "gate_probability = 1.2\n",
            12,
            "tracker.gate_probability",
            "1.2: must lie in (0, 1)",
        );
        fails("max_speed = -1\n", 12, "tracker.max_speed", positive);
        fails(
            "velocity_gate_sigmas = -1.0\n",
            12,
            "tracker.velocity_gate_sigmas",
            "non-negative",
        );
        fails(
            "max_initiation_interval = 0\n",
            12,
            "tracker.max_initiation_interval",
            positive,
        );
        fails(
            "max_position_sigma = 0.0\n",
            12,
            "tracker.max_position_sigma",
            positive,
        );
        fails("grid_cell = 0\n", 12, "tracker.grid_cell", positive);
        fails(
            "confirm_n = 40\n",
            12,
            "tracker.confirm_n",
            "40: must lie in 2..=32",
        );
        fails(
            "confirm_m = 5\nconfirm_n = 4\n",
            12,
            "tracker.confirm_m",
            "5: must lie in 2..=confirm_n",
        );
        // A default refused (confirm_m = 3 > confirm_n): the [tracker] line.
        fails(
            "confirm_n = 2\n",
            11,
            "tracker.confirm_m",
            "3: must lie in 2..=confirm_n",
        );
        fails("max_misses = 0\n", 12, "tracker.max_misses", "at least 1");
        fails(
            &JPDA.replace("0.9", "1.5"),
            13,
            "tracker.p_detection",
            "1.5: must lie in (0, 1]",
        );
        fails(
            &JPDA.replace("1e-9", "0.0"),
            14,
            "tracker.clutter_density",
            positive,
        );
        fails(
            &format!("{JPDA}max_exact_events = 0\n"),
            15,
            "tracker.max_exact_events",
            "at least 1",
        );
        for (key, bad, line) in [
            ("p_detection", "1.5", 13),
            ("clutter_density", "0", 14),
            ("new_target_density", "-1", 15),
            ("false_confirm", "0.6", 16),
            ("missed_confirm", "0.7", 17),
            ("delete_drop", "0", 18),
        ] {
            let start = SCORE.find(&format!("{key} =")).unwrap();
            let end = start + SCORE[start..].find('\n').unwrap();
            let text = format!("{}{key} = {bad}{}", &SCORE[..start], &SCORE[end..]);
            fails(&text, line, &format!("tracker.score.{key}"), bad);
        }
    }

    #[test]
    fn tracker_checks_of_sensors_and_estimators_name_their_key() {
        let sensor = |id: u32, polar: &str| {
            format!("[[sensor]]\nid = {id}\nposition = [0.0, 0.0]\n{polar}\n")
        };
        let polar = "sigma_range = 50.0\nsigma_azimuth_deg = 0.06\n";
        let kf = "[estimator]\nkind = \"kf-converted\"\nsigma_a = 2.0\n";
        let imm = |models: &str, markov: &str, more: &str| {
            format!("[estimator]\nkind = \"imm\"\nmodels = [{models}]\nmarkov = {markov}\n{more}")
        };
        let cv2 = "{ kind = \"cv\", sigma_a = 0.5 }, { kind = \"cv\", sigma_a = 10.0 }";
        let m2 = "[[0.95, 0.05], [0.05, 0.95]]";
        let multi = |more: &str| imm(cv2, m2, more).replace("\"imm\"", "\"multi-imm\"");
        // After one polar sensor (lines 1–6) `[estimator]` is line 7, `models` line 9.
        let one = sensor(1, polar);
        let cases: Vec<(String, Option<u64>, &str, &str)> = vec![
            (
                format!("{}{kf}", one.replace("50.0", "0.0")),
                Some(4),
                "sigma_range",
                "sensor 1: must be finite and positive",
            ),
            (
                format!("{}{kf}", one.replace("0.06", "0.0")),
                Some(5),
                "sigma_azimuth_deg",
                "sensor 1: must be finite and positive",
            ),
            (
                format!("{one}{}{}", sensor(2, ""), multi("")),
                Some(8),
                "sigma_range",
                "sensor 2: the multi-IMM needs every sensor's polar noise",
            ),
            (kf.to_owned(), None, "sensor", "at least one [[sensor]]"),
            (
                format!(
                    "{one}{}",
                    imm(
                        &format!("{cv2}, {{ kind = \"cv\", sigma_a = 1.0 }}"),
                        "[[0.9, 0.05, 0.05], [0.05, 0.9, 0.05], [0.05, 0.05, 0.9]]",
                        ""
                    )
                ),
                Some(9),
                "estimator.models",
                "not 3",
            ),
            (
                format!(
                    "{one}{}",
                    imm(
                        "{ kind = \"cv\", sigma_a = 0.5 }, { kind = \"ct\", sigma_a = 1.0, rate_deg = 3.0 }",
                        m2,
                        ""
                    )
                ),
                Some(9),
                "estimator.models",
                "CT models are not built",
            ),
            (
                format!("{one}{}", imm(cv2, "[[0.95, 0.05], [0.1, 0.9]]", "")),
                Some(10),
                "estimator.markov",
                "(here 0.95 and 0.9)",
            ),
            (
                format!("{one}{}", imm(cv2, "[[1.0, 0.0], [0.0, 1.0]]", "")),
                Some(10),
                "estimator.markov",
                "1: must lie in (0, 1)",
            ),
            (
                format!("{one}{}", imm(cv2, m2, "initial = [0.3, 0.7]\n")),
                Some(11),
                "estimator.initial",
                "both modes at 0.5",
            ),
            (
                format!("{one}{}", multi("n = 3\n")),
                Some(11),
                "estimator.n",
                "not 3",
            ),
            (
                format!("{one}{}", multi("per_axis = true\n")),
                Some(11),
                "estimator.per_axis",
                "one factor",
            ),
            (
                format!("{one}{}[tracker]\n{JPDA}", multi("")),
                Some(12),
                "tracker.association",
                "JPDA with the multi-IMM estimator is not built",
            ),
        ];
        for (text, line, field, msg) in cases {
            let text = if text.contains("[tracker]") {
                text
            } else {
                format!("{text}\n[tracker]\n")
            };
            let e = load_text(&text).unwrap_err();
            assert_eq!(at(&e), (line, Some(field.to_owned())), "{text}\n→ {e}");
            assert!(e.to_string().contains(msg), "{text}\n→ {e}");
        }
    }
}

mod tracker_keys {
    use super::*;

    const HEAD: &str = "[[sensor]]\nid = 1\nposition = [10.0, 20.0]\nsigma_range = 50.0\nsigma_azimuth_deg = 0.06\n\n[estimator]\nkind = \"kf-converted\"\nsigma_a = 1.5\n";

    fn multi(text: &str) -> MultiTarget {
        match load_text(text) {
            Ok(Job::Multi(m)) => m,
            other => panic!("not a multi-target job: {other:?}"),
        }
    }

    #[test]
    fn every_key_reaches_its_field() {
        // Distinct values per key, so that a key mapped to the wrong field shows.
        let text = format!(
            "{HEAD}[tracker]\nassociation = \"jpda\"\np_detection = 0.8\nclutter_density = 2e-9\nmax_exact_events = 77\ngate_probability = 0.95\nmax_speed = 400\nvelocity_gate_sigmas = 2.5\nmax_initiation_interval = 11.0\nconfirm_m = 4\nconfirm_n = 6\nmax_misses = 5\nmax_position_sigma = 3000.0\ngrid_cell = 1500.0\n[tracker.score]\np_detection = 0.7\nclutter_density = 3e-9\nnew_target_density = 4e-10\nfalse_confirm = 0.01\nmissed_confirm = 0.2\ndelete_drop = 6.0\n"
        );
        let m = multi(&text);
        let c = &m.config;
        // Parsed decimal values: equal to round-off.
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-15 * b.abs();
        assert_eq!(m.estimator, "kf-converted");
        assert!(close(c.sigma_a, 1.5));
        assert!(close(c.gate_probability, 0.95));
        assert!(close(c.max_speed, 400.0));
        assert!(close(c.velocity_gate_sigmas, 2.5));
        assert!(close(c.max_initiation_interval, 11.0));
        assert_eq!((c.confirm_m, c.confirm_n, c.max_misses), (4, 6, 5));
        assert!(close(c.max_position_sigma, 3000.0));
        assert!(close(c.grid_cell, 1500.0));
        let AssociationConfig::Jpda {
            p_detection,
            clutter_density,
            max_exact_events,
        } = c.association
        else {
            panic!("not JPDA: {:?}", c.association);
        };
        assert!(close(p_detection, 0.8) && close(clutter_density, 2e-9));
        assert_eq!(max_exact_events, 77);
        let s = c.score.unwrap();
        assert!(close(s.p_detection, 0.7) && close(s.clutter_density, 3e-9));
        assert!(close(s.new_target_density, 4e-10) && close(s.delete_drop, 6.0));
        assert!(close(s.false_confirm, 0.01) && close(s.missed_confirm, 0.2));
        assert_eq!(c.estimator, EstimatorConfig::Kf);
        // The sensor with its position and polar noise (0.06° in radians).
        assert_eq!(c.sensors.len(), 1);
        assert_eq!(c.sensors[0].id, SensorId(1));
        let n = c.sensors[0].polar_noise.unwrap();
        assert!(close(n.sigma_range, 50.0) && close(n.sigma_azimuth, 0.06_f64.to_radians()));
        assert!(close(c.sensors[0].position[0], 10.0) && close(c.sensors[0].position[1], 20.0));
    }

    #[test]
    fn defaults_are_the_libraries_and_the_estimators() {
        let m = multi(&format!("{HEAD}[tracker]\n"));
        let mut expected = TrackerConfig::new(m.config.sensors.clone());
        expected.sigma_a = 1.5;
        assert_eq!(m.config, expected);
        // JPDA's max_exact_events defaults to the CLI's constant.
        let m = multi(&format!(
            "{HEAD}[tracker]\nassociation = \"jpda\"\np_detection = 0.9\nclutter_density = 1e-9\n"
        ));
        assert!(matches!(
            m.config.association,
            AssociationConfig::Jpda { max_exact_events, .. } if max_exact_events == DEFAULT_MAX_EXACT_EVENTS as usize
        ));
        // The multi-IMM's grid spacing and clip: the single-target defaults (p = 0.1,
        // 5 %), or as written (clip = 0: none).
        let mimm = "kind = \"multi-imm\"\nmodels = [{ kind = \"cv\", sigma_a = 0.5 }, { kind = \"cv\", sigma_a = 10.0 }]\nmarkov = [[0.95, 0.05], [0.05, 0.95]]\n";
        let text = HEAD.replace("kind = \"kf-converted\"\nsigma_a = 1.5\n", mimm);
        let m = multi(&format!("{text}[tracker]\n"));
        assert_eq!(
            m.config.estimator,
            EstimatorConfig::MultiImm {
                sigma_a_low: 0.5,
                sigma_a_high: 10.0,
                p_stay: 0.95,
                grid_spacing: 0.1,
                clip: Some(0.05),
            }
        );
        let m = multi(&format!("{text}clip = 0.0\np = 0.2\n[tracker]\n"));
        assert!(matches!(
            m.config.estimator,
            EstimatorConfig::MultiImm { clip: None, grid_spacing, .. } if grid_spacing.to_bits() == 0.2_f64.to_bits()
        ));
    }

    #[test]
    fn bad_tracker_values_name_their_line() {
        let score = "[tracker.score]\np_detection = 0.9\nclutter_density = 1e-9\nnew_target_density = 1e-10\nfalse_confirm = 0.01\nmissed_confirm = 0.1\ndelete_drop = 5.0\n";
        // `[tracker]` is line 11; its first key line 12.
        let cases: [(String, u64, Option<&str>, &str); 12] = [
            ("confirm_k = 3\n".into(), 12, None, "unknown field `confirm_k`"),
            (format!("{score}extra = 1\n"), 19, None, "unknown field `extra`"),
            ("[tracker.score]\np_detection = 0.9\n".into(), 12, None, "missing field `clutter_density`"),
            (score.replace("5.0", "\"x\""), 18, Some("tracker.score.delete_drop"), "\"x\" is not a number"),
            ("association = 3\n".into(), 12, Some("tracker.association"), "3 is not a string"),
            ("association = \"mht\"\n".into(), 12, Some("tracker.association"), "unknown association \"mht\""),
            ("p_detection = 0.9\n".into(), 12, Some("tracker.p_detection"), "used by association = \"jpda\" only"),
            ("association = \"jpda\"\nclutter_density = 1e-9\n".into(), 11, Some("tracker.p_detection"), "required by association = \"jpda\""),
            ("association = \"jpda\"\np_detection = 0.9\n".into(), 11, Some("tracker.clutter_density"), "required"),
            ("association = \"jpda\"\np_detection = 0.9\nclutter_density = 1e-9\nmax_exact_events = -1\n".into(), 15, Some("tracker.max_exact_events"), "-1 is not a count"),
            ("confirm_m = 1.5\n".into(), 12, Some("tracker.confirm_m"), "1.5 is not an integer"),
            ("max_speed = \"fast\"\n".into(), 12, Some("tracker.max_speed"), "\"fast\" is not a number"),
        ];
        for (tracker, line, field, msg) in cases {
            let text = format!("{HEAD}\n[tracker]\n{tracker}");
            let e = load_text(&text).unwrap_err();
            assert_eq!(
                at(&e),
                (Some(line), field.map(str::to_owned)),
                "{text}\n→ {e}"
            );
            assert!(e.to_string().contains(msg), "{text}\n→ {e}");
        }
    }
}

mod from_text {
    use super::*;

    #[test]
    fn text_is_named_as_a_file_is() {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../docs/examples/tracker.toml"
        ))
        .unwrap();
        let from_text = crate::load_text(&text, std::path::Path::new("config.toml")).unwrap();
        assert!(matches!(from_text.job, Job::Multi(_)));
        let bad = text.replace("max_speed = 350.0", "max_speed = -1.0");
        let e = crate::load_text(&bad, std::path::Path::new("config.toml")).unwrap_err();
        let via_file = load_text(&bad).unwrap_err();
        assert_eq!(at(&e), at(&via_file));
        assert!(e.to_string().starts_with("config.toml:"), "{e}");
        // A file that cannot be read is still an I/O error naming it.
        let missing = load(std::path::Path::new("no/such/config.toml")).unwrap_err();
        assert!(matches!(missing, ConfigError::Io { .. }), "{missing}");
    }
}
