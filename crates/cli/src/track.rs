//! `argus track`: a configured estimator over a user's plot file (see `docs/FORMATS.md`).

use std::path::Path;

use argus_core_math::{Gaussian, Matrix, Vector};
use serde::Deserialize;
use toml::Spanned;

use crate::error::CliError;
use argus_filters::{two_point_cv2, two_point_cv3};

use crate::estimator::{
    cv_ekf, cv_kf, cv3_ekf, cv3_kf, polar, position, position3, spherical, step, unbiased,
    unbiased3,
};
use crate::output::write_atomic;
use crate::plotfile::{self, FilePlot, FileValue};

/// The TOML configuration.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Config {
    #[serde(rename = "sensor", default)]
    sensors: Vec<SensorConfig>,
    estimator: EstimatorConfig,
}

/// A sensor: id and position (`[x, y]` or `[x, y, z]`); polar sensors also their noise,
/// spherical ones also the elevation noise.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SensorConfig {
    id: u32,
    position: Spanned<Vec<f64>>,
    sigma_range: Option<Spanned<f64>>,
    sigma_azimuth_deg: Option<Spanned<f64>>,
    sigma_elevation_deg: Option<Spanned<f64>>,
}

/// One motion model of an IMM: `kind = "cv"` or `"ct"` (with `rate_deg`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ModelConfig {
    kind: ModelKind,
    sigma_a: Spanned<f64>,
    rate_deg: Option<Spanned<f64>>,
}

/// Motion-model kinds.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum ModelKind {
    /// Constant velocity.
    Cv,
    /// Coordinated turn at a fixed rate.
    Ct,
}

/// Estimator kinds: later issues add theirs (multi-IMM, trackers).
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum EstimatorKind {
    /// KF on converted plots (polar plots: unbiased conversion; Cartesian: as reported).
    KfConverted,
    /// EKF on polar plots.
    Ekf,
    /// IMM: validated here; runs once `argus-imm` is wired in.
    Imm,
}

/// The `[estimator]` table as written (flat, so that every value keeps its position in
/// the file for error messages); [`load`] turns it into the [`Estimator`] enum.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct EstimatorConfig {
    kind: EstimatorKind,
    sigma_a: Option<Spanned<f64>>,
    models: Option<Vec<ModelConfig>>,
    markov: Option<Spanned<Vec<Vec<f64>>>>,
}

fn line_of(text: &str, offset: usize) -> u64 {
    text.get(..offset)
        .map_or(0, |s| s.matches('\n').count() as u64 + 1)
}

fn non_negative(path: &Path, text: &str, field: &str, v: &Spanned<f64>) -> Result<f64, CliError> {
    let x = *v.get_ref();
    if x.is_finite() && x >= 0.0 {
        Ok(x)
    } else {
        Err(CliError::input(
            path,
            Some(line_of(text, v.span().start)),
            Some(field),
            format!("{x} must be finite and non-negative (a standard deviation)"),
        ))
    }
}

/// Checks the Markov matrix: square, one row per model, entries in [0, 1], rows summing
/// to 1 within 1e-9.
fn check_markov(
    path: &Path,
    text: &str,
    m: &Spanned<Vec<Vec<f64>>>,
    n: usize,
) -> Result<(), CliError> {
    let line = Some(line_of(text, m.span().start));
    let rows = m.get_ref();
    if rows.len() != n || rows.iter().any(|r| r.len() != n) {
        return Err(CliError::input(
            path,
            line,
            Some("markov"),
            format!("must be {n} × {n} (one row and column per model)"),
        ));
    }
    for (i, r) in rows.iter().enumerate() {
        let sum: f64 = r.iter().sum();
        if r.iter().any(|p| !(0.0..=1.0).contains(p)) || (sum - 1.0).abs() > 1e-9 {
            return Err(CliError::input(
                path,
                line,
                Some("markov"),
                format!(
                    "row {} is not stochastic (entries in [0, 1] summing to 1; sum = {sum})",
                    i + 1
                ),
            ));
        }
    }
    Ok(())
}

/// A validated estimator: its kind and the CV model's white-acceleration σ (m/s²). The
/// filter is built for the plot file's dimension (2-D or 3-D CV).
#[derive(Debug, Clone, Copy)]
enum Estimator {
    KfConverted(f64),
    Ekf(f64),
}

/// A validated sensor.
#[derive(Debug, Clone, Copy)]
struct Sensor {
    id: u32,
    /// `[x, y, z]` (z = 0 when the config gives two coordinates).
    position: [f64; 3],
    /// Range σ (m), azimuth σ (rad).
    polar: Option<(f64, f64)>,
    /// Elevation σ (rad).
    sigma_elevation: Option<f64>,
}

fn load(path: &Path) -> Result<(Vec<Sensor>, Estimator), CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| CliError::io(path, e))?;
    let cfg: Config = toml::from_str(&text).map_err(|e| {
        let line = e.span().map(|s| line_of(&text, s.start));
        CliError::input(path, line, None, e.message().to_owned())
    })?;
    let mut sensors = Vec::new();
    for s in &cfg.sensors {
        let pos = s.position.get_ref();
        let pos_line = Some(line_of(&text, s.position.span().start));
        let position = match pos.as_slice() {
            [x, y] => [*x, *y, 0.0],
            [x, y, z] => [*x, *y, *z],
            _ => {
                return Err(CliError::input(
                    path,
                    pos_line,
                    Some("position"),
                    format!(
                        "sensor {}: position needs 2 or 3 coordinates, not {}",
                        s.id,
                        pos.len()
                    ),
                ));
            }
        };
        if !position.iter().all(|v| v.is_finite()) {
            return Err(CliError::input(
                path,
                pos_line,
                Some("position"),
                format!("sensor {}: position must be finite", s.id),
            ));
        }
        let polar = match (&s.sigma_range, &s.sigma_azimuth_deg) {
            (Some(r), Some(a)) => Some((
                non_negative(path, &text, "sigma_range", r)?,
                non_negative(path, &text, "sigma_azimuth_deg", a)?.to_radians(),
            )),
            _ => None,
        };
        if sensors.iter().any(|o: &Sensor| o.id == s.id) {
            return Err(CliError::input(
                path,
                None,
                Some("id"),
                format!("sensor id {} given twice", s.id),
            ));
        }
        let sigma_elevation = match &s.sigma_elevation_deg {
            Some(e) => Some(non_negative(path, &text, "sigma_elevation_deg", e)?.to_radians()),
            None => None,
        };
        sensors.push(Sensor {
            id: s.id,
            position,
            polar,
            sigma_elevation,
        });
    }
    let e = &cfg.estimator;
    let missing = |key: &str| {
        CliError::input(
            path,
            None,
            Some(key),
            format!("required by estimator kind {:?}", e.kind),
        )
    };
    let est = match e.kind {
        EstimatorKind::KfConverted => {
            let sa = e.sigma_a.as_ref().ok_or_else(|| missing("sigma_a"))?;
            Estimator::KfConverted(non_negative(path, &text, "sigma_a", sa)?)
        }
        EstimatorKind::Ekf => {
            let sa = e.sigma_a.as_ref().ok_or_else(|| missing("sigma_a"))?;
            Estimator::Ekf(non_negative(path, &text, "sigma_a", sa)?)
        }
        EstimatorKind::Imm => {
            let models = e.models.as_ref().ok_or_else(|| missing("models"))?;
            for m in models {
                non_negative(path, &text, "sigma_a", &m.sigma_a)?;
                match (m.kind, &m.rate_deg) {
                    (ModelKind::Ct, Some(w)) if !w.get_ref().is_finite() => {
                        return Err(CliError::input(
                            path,
                            Some(line_of(&text, w.span().start)),
                            Some("rate_deg"),
                            format!("{} must be finite", w.get_ref()),
                        ));
                    }
                    (ModelKind::Ct, None) => return Err(missing("rate_deg")),
                    _ => {}
                }
            }
            let markov = e.markov.as_ref().ok_or_else(|| missing("markov"))?;
            check_markov(path, &text, markov, models.len())?;
            return Err(CliError::input(
                path,
                None,
                Some("estimator.kind"),
                "'imm' is a valid configuration but cannot run yet: it needs the argus-imm crate wired into `argus track` (a later issue)",
            ));
        }
    };
    Ok((sensors, est))
}

/// Runs `argus track`: 2-D plot files with a 2-D CV estimator, 3-D ones (spherical or
/// Cartesian 3-D) with a 3-D CV estimator. Returns the number of track points written.
///
/// # Errors
/// [`CliError::Input`] for bad configuration or plots, filter errors, I/O.
pub(crate) fn run(config: &Path, plots_path: &Path, out: &Path) -> Result<usize, CliError> {
    let (sensors, est) = load(config)?;
    let plots = plotfile::read(plots_path)?;
    let ctx = Ctx {
        config,
        plots_path,
        sensors: &sensors,
    };
    let (rows, n) = if plots.first().is_some_and(|p| p.value.dim() == 3) {
        track_3d(&ctx, est, &plots)?
    } else {
        track_2d(&ctx, est, &plots)?
    };
    write_atomic(out, rows.as_bytes())?;
    Ok(n)
}

/// What the per-dimension trackers need to name errors.
struct Ctx<'a> {
    config: &'a Path,
    plots_path: &'a Path,
    sensors: &'a [Sensor],
}

impl Ctx<'_> {
    fn sensor(&self, p: &FilePlot) -> Result<&Sensor, CliError> {
        self.sensors
            .iter()
            .find(|s| s.id == p.sensor)
            .ok_or_else(|| {
                CliError::input(
                    self.plots_path,
                    Some(p.line),
                    Some("sensor"),
                    format!(
                        "unknown sensor {} (not in {})",
                        p.sensor,
                        self.config.display()
                    ),
                )
            })
    }

    /// Range and azimuth σ of the plot's sensor.
    fn polar_sigmas(&self, s: &Sensor) -> Result<(f64, f64), CliError> {
        s.polar.ok_or_else(|| {
            CliError::input(
                self.config,
                None,
                Some("sigma_range"),
                format!(
                    "sensor {} reports polar/spherical plots but has no sigma_range / sigma_azimuth_deg",
                    s.id
                ),
            )
        })
    }

    /// Range, azimuth and elevation σ of the plot's sensor.
    fn spherical_sigmas(&self, s: &Sensor) -> Result<[f64; 3], CliError> {
        let (sr, sa) = self.polar_sigmas(s)?;
        let se = s.sigma_elevation.ok_or_else(|| {
            CliError::input(
                self.config,
                None,
                Some("sigma_elevation_deg"),
                format!(
                    "sensor {} reports spherical plots but has no sigma_elevation_deg",
                    s.id
                ),
            )
        })?;
        Ok([sr, sa, se])
    }

    fn filter_error(&self, p: &FilePlot) -> impl Fn(argus_filters::FilterError) -> CliError {
        let (path, line) = (self.plots_path.to_path_buf(), p.line);
        move |e| {
            CliError::input(
                &path,
                Some(line),
                None,
                format!("filter update failed: {e}"),
            )
        }
    }
}

/// The generic loop: two-point start on the first two plots, then one predict + update
/// per plot, one CSV row per estimate (`t,track,` state, covariance diagonal).
fn track_loop<const N: usize, const D: usize>(
    ctx: &Ctx<'_>,
    plots: &[FilePlot],
    convert: impl Fn(&FilePlot) -> Result<(Vector<D>, Matrix<D, D>), CliError>,
    init: impl Fn(
        &Vector<D>,
        &Matrix<D, D>,
        &Vector<D>,
        &Matrix<D, D>,
        f64,
    ) -> Result<Gaussian<N>, argus_filters::FilterError>,
    update: impl Fn(&Gaussian<N>, f64, &FilePlot) -> Result<Gaussian<N>, CliError>,
) -> Result<(String, usize), CliError> {
    const AXES: [&str; 3] = ["x", "y", "z"];
    let mut cols = vec!["t".to_owned(), "track".to_owned()];
    let names: Vec<String> = AXES
        .iter()
        .take(N / 2)
        .flat_map(|a| [(*a).to_owned(), format!("v{a}")])
        .collect();
    cols.extend(names.iter().cloned());
    cols.extend(names.iter().map(|n| format!("var_{n}")));
    let mut rows = cols.join(",");
    rows.push('\n');
    let mut iter = plots.iter();
    let (Some(p1), Some(p2)) = (iter.next(), iter.next()) else {
        return Err(CliError::input(
            ctx.plots_path,
            None,
            None,
            "at least two plots are needed to start a track",
        ));
    };
    let (z1, r1) = convert(p1)?;
    let (z2, r2) = convert(p2)?;
    let mut x = init(&z1, &r1, &z2, &r2, p2.time - p1.time).map_err(|e| {
        CliError::input(
            ctx.plots_path,
            Some(p2.line),
            Some("t"),
            format!("two-point initialisation: {e}"),
        )
    })?;
    let mut t = p2.time;
    let push = |rows: &mut String, t: f64, g: &Gaussian<N>| {
        let mut v = vec![format!("{t}"), "1".to_owned()];
        v.extend(g.mean().iter().map(|m| format!("{m}")));
        v.extend((0..N).map(|i| format!("{}", g.cov()[(i, i)])));
        rows.push_str(&v.join(","));
        rows.push('\n');
    };
    push(&mut rows, t, &x);
    let mut n = 1;
    for p in iter {
        x = update(&x, p.time - t, p)?;
        t = p.time;
        push(&mut rows, t, &x);
        n += 1;
    }
    Ok((rows, n))
}

fn wrong_dim(ctx: &Ctx<'_>, p: &FilePlot) -> CliError {
    CliError::input(
        ctx.plots_path,
        Some(p.line),
        None,
        "plot of another dimension than the file's first plot",
    )
}

/// 2-D plots (polar or Cartesian) with a CV model on `[x, vx, y, vy]`.
fn track_2d(
    ctx: &Ctx<'_>,
    est: Estimator,
    plots: &[FilePlot],
) -> Result<(String, usize), CliError> {
    let convert = |p: &FilePlot| -> Result<(Vector<2>, Matrix<2, 2>), CliError> {
        let s = ctx.sensor(p)?;
        match p.value {
            FileValue::Cartesian { x, y, cov } => Ok((
                Vector::<2>::new(x, y),
                Matrix::<2, 2>::new(cov[0], cov[1], cov[1], cov[2]),
            )),
            FileValue::Polar { range, azimuth } => {
                let (sr, sa) = ctx.polar_sigmas(s)?;
                let (z, r) = unbiased(range, azimuth, sr, sa).map_err(|e| {
                    CliError::input(ctx.plots_path, Some(p.line), Some("range"), e.to_string())
                })?;
                Ok((z + Vector::<2>::new(s.position[0], s.position[1]), r))
            }
            FileValue::Spherical { .. } | FileValue::Cartesian3 { .. } => Err(wrong_dim(ctx, p)),
        }
    };
    match est {
        Estimator::KfConverted(sa) => {
            let f = cv_kf(sa)?;
            track_loop(ctx, plots, convert, two_point_cv2, |x, dt, p| {
                let (z, r) = convert(p)?;
                Ok(step(&f, x, dt, &position(r)?, &z)
                    .map_err(ctx.filter_error(p))?
                    .0)
            })
        }
        Estimator::Ekf(sa) => {
            let f = cv_ekf(sa)?;
            track_loop(ctx, plots, convert, two_point_cv2, |x, dt, p| {
                let post = if let FileValue::Polar { range, azimuth } = p.value {
                    let s = ctx.sensor(p)?;
                    let (sr, sa) = ctx.polar_sigmas(s)?;
                    let m = polar([s.position[0], s.position[1]], sr, sa)?;
                    step(&f, x, dt, &m, &Vector::<2>::new(range, azimuth))
                } else {
                    let (z, r) = convert(p)?;
                    step(&f, x, dt, &position(r)?, &z)
                };
                Ok(post.map_err(ctx.filter_error(p))?.0)
            })
        }
    }
}

/// 3-D plots (spherical or Cartesian) with a CV model on `[x, vx, y, vy, z, vz]`.
fn track_3d(
    ctx: &Ctx<'_>,
    est: Estimator,
    plots: &[FilePlot],
) -> Result<(String, usize), CliError> {
    let convert = |p: &FilePlot| -> Result<(Vector<3>, Matrix<3, 3>), CliError> {
        let s = ctx.sensor(p)?;
        match p.value {
            FileValue::Cartesian3 { p: q, cov } => Ok((
                Vector::<3>::new(q[0], q[1], q[2]),
                Matrix::<3, 3>::new(
                    cov[0], cov[1], cov[2], cov[1], cov[3], cov[4], cov[2], cov[4], cov[5],
                ),
            )),
            FileValue::Spherical {
                range,
                azimuth,
                elevation,
            } => {
                let sig = ctx.spherical_sigmas(s)?;
                let (z, r) = unbiased3(range, azimuth, elevation, sig).map_err(|e| {
                    CliError::input(ctx.plots_path, Some(p.line), Some("range"), e.to_string())
                })?;
                Ok((z + Vector::<3>::from(s.position), r))
            }
            FileValue::Polar { .. } | FileValue::Cartesian { .. } => Err(wrong_dim(ctx, p)),
        }
    };
    match est {
        Estimator::KfConverted(sa) => {
            let f = cv3_kf(sa)?;
            track_loop(ctx, plots, convert, two_point_cv3, |x, dt, p| {
                let (z, r) = convert(p)?;
                Ok(step(&f, x, dt, &position3(r)?, &z)
                    .map_err(ctx.filter_error(p))?
                    .0)
            })
        }
        Estimator::Ekf(sa) => {
            let f = cv3_ekf(sa)?;
            track_loop(ctx, plots, convert, two_point_cv3, |x, dt, p| {
                let post = if let FileValue::Spherical {
                    range,
                    azimuth,
                    elevation,
                } = p.value
                {
                    let s = ctx.sensor(p)?;
                    let m = spherical(s.position, ctx.spherical_sigmas(s)?)?;
                    step(&f, x, dt, &m, &Vector::<3>::new(range, azimuth, elevation))
                } else {
                    let (z, r) = convert(p)?;
                    step(&f, x, dt, &position3(r)?, &z)
                };
                Ok(post.map_err(ctx.filter_error(p))?.0)
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load_text(text: &str) -> Result<(Vec<Sensor>, Estimator), CliError> {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("f.toml");
        std::fs::write(&p, text).unwrap();
        load(&p)
    }

    fn at(e: &CliError) -> (Option<u64>, Option<String>) {
        match e {
            CliError::Input { at, .. } => (at.line, at.field.clone()),
            other => panic!("not an input error: {other}"),
        }
    }

    const GOOD: &str = "[[sensor]]\nid = 3\nposition = [1.0, 2.0, 3.0]\nsigma_range = 10.0\nsigma_azimuth_deg = 0.5\nsigma_elevation_deg = 0.25\n\n[estimator]\nkind = \"ekf\"\nsigma_a = 2.0\n";

    #[test]
    fn good_config_is_typed() {
        let (s, e) = load_text(GOOD).unwrap();
        assert_eq!(s.len(), 1);
        assert_eq!(s[0].id, 3);
        // Parsed exactly: compare bits.
        assert_eq!(
            s[0].position.map(f64::to_bits),
            [1.0f64, 2.0, 3.0].map(f64::to_bits)
        );
        let (sr, sa) = s[0].polar.unwrap();
        assert!((sr - 10.0).abs() < 1e-15);
        // 0.5° and 0.25° in radians: π/360 and π/720.
        assert!((sa - std::f64::consts::PI / 360.0).abs() < 1e-15);
        assert!((s[0].sigma_elevation.unwrap() - std::f64::consts::PI / 720.0).abs() < 1e-15);
        assert!(matches!(e, Estimator::Ekf(v) if (v - 2.0).abs() < 1e-15));
        // A 2-D position gets z = 0.
        let (s, _) = load_text(&GOOD.replace("[1.0, 2.0, 3.0]", "[1.0, 2.0]")).unwrap();
        assert_eq!(
            s[0].position.map(f64::to_bits),
            [1.0f64, 2.0, 0.0].map(f64::to_bits)
        );
    }

    #[test]
    fn bad_values_name_their_line() {
        let e = load_text(&GOOD.replace("[1.0, 2.0, 3.0]", "[1.0, 2.0, 3.0, 4.0]")).unwrap_err();
        assert_eq!(at(&e), (Some(3), Some("position".into())));
        let e = load_text(&GOOD.replace("0.25", "-0.25")).unwrap_err();
        assert_eq!(at(&e), (Some(6), Some("sigma_elevation_deg".into())));
        let e = load_text(&GOOD.replace("sigma_a = 2.0", "sigma_a = -2.0")).unwrap_err();
        assert_eq!(at(&e), (Some(10), Some("sigma_a".into())));
        let e = load_text(&GOOD.replace("\"ekf\"", "\"ukf\"")).unwrap_err();
        assert_eq!(at(&e).0, Some(9));
        let twice = format!("{}\n{}", &GOOD[..GOOD.find("[estimator]").unwrap()], GOOD);
        let e = load_text(&twice).unwrap_err();
        assert_eq!(at(&e).1.as_deref(), Some("id"));
    }

    #[test]
    fn markov_rows_must_be_stochastic() {
        let imm = |m: &str| {
            format!(
                "[estimator]\nkind = \"imm\"\nmodels = [{{ kind = \"cv\", sigma_a = 0.1 }}, {{ kind = \"ct\", sigma_a = 0.5, rate_deg = 3.0 }}]\nmarkov = {m}\n"
            )
        };
        let e = load_text(&imm("[[0.9, 0.1], [0.1, 0.8]]")).unwrap_err();
        assert_eq!(at(&e), (Some(4), Some("markov".into())));
        let e = load_text(&imm("[[1.1, -0.1], [0.1, 0.9]]")).unwrap_err();
        assert_eq!(at(&e), (Some(4), Some("markov".into())));
        let e = load_text(&imm("[[1.0]]")).unwrap_err();
        assert_eq!(at(&e), (Some(4), Some("markov".into())));
    }
}
