//! `argus track`: a configured estimator over a user's plot file (see `docs/FORMATS.md`).

use argus_sensors::Measurement;
use std::path::Path;

use argus_core_math::{Gaussian, Matrix, Vector};
use serde::Deserialize;
use toml::Spanned;

use crate::error::CliError;
use argus_filters::{two_point_cv2, two_point_cv3};

use crate::estimator::{
    ImmSpec, MAX_MODELS, MultiSpec, build_imm, cv_ekf, cv_kf, cv3_ekf, cv3_kf,
    initial_probabilities, polar, position, position3, spherical, step, unbiased, unbiased3,
};
use crate::output::write_atomic;
use crate::plotfile::{self, FilePlot};
use argus_imm::{
    ImmEstimate, MultiImm, MultiImmEstimate, NoiseGrid, NoiseVariances, PROBABILITY_SUM_TOL,
    UnbiasedConversion,
};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};

/// The TOML configuration.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Config {
    #[serde(rename = "sensor", default)]
    sensors: Vec<SensorConfig>,
    estimator: EstimatorConfig,
    /// Multi-target mode: read by `track_multi.rs`.
    #[serde(default, rename = "tracker")]
    _tracker: Option<serde::de::IgnoredAny>,
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
    /// IMM of CV / fixed-rate CT Kalman filters on converted plots (seed 000).
    Imm,
    /// The multi-IMM measurement-noise estimator of seed 000 eqs (8)–(14) around that IMM.
    MultiImm,
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
    initial: Option<Spanned<Vec<f64>>>,
    n: Option<Spanned<i64>>,
    p: Option<Spanned<f64>>,
    clip: Option<Spanned<f64>>,
    per_axis: Option<bool>,
}

/// The 1-based line of byte `offset` of `text`.
pub(crate) fn line_of(text: &str, offset: usize) -> u64 {
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

/// A validated estimator: its kind and the CV model's white-acceleration σ (m/s²), or the
/// IMM (and multi-IMM) description. The KF and EKF are built for the plot file's dimension
/// (2-D or 3-D CV); the IMMs are 2-D.
#[derive(Debug, Clone)]
enum Estimator {
    KfConverted(f64),
    Ekf(f64),
    Imm(ImmSpec),
    MultiImm(ImmSpec, MultiSpec),
}

/// A validated sensor.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sensor {
    pub(crate) id: u32,
    /// `[x, y, z]` (z = 0 when the config gives two coordinates).
    pub(crate) position: [f64; 3],
    /// Range σ (m), azimuth σ (rad).
    pub(crate) polar: Option<(f64, f64)>,
    /// Elevation σ (rad).
    pub(crate) sigma_elevation: Option<f64>,
}

/// Validates the IMM keys (`models`, `markov`, `initial`) and builds the motion models.
fn imm_spec(path: &Path, text: &str, e: &EstimatorConfig) -> Result<ImmSpec, CliError> {
    let missing = |key: &str| {
        CliError::input(
            path,
            None,
            Some(key),
            format!("required by estimator kind {:?}", e.kind),
        )
    };
    let models = e.models.as_ref().ok_or_else(|| missing("models"))?;
    if models.is_empty() || models.len() > MAX_MODELS {
        return Err(CliError::input(
            path,
            None,
            Some("models"),
            format!("1 to {MAX_MODELS} models, not {}", models.len()),
        ));
    }
    let mut built = Vec::with_capacity(models.len());
    for m in models {
        let sa = non_negative(path, text, "sigma_a", &m.sigma_a)?;
        let model = match (m.kind, &m.rate_deg) {
            (ModelKind::Ct, Some(w)) => {
                let rate = *w.get_ref();
                if !(rate.is_finite() && rate != 0.0) {
                    return Err(CliError::input(
                        path,
                        Some(line_of(text, w.span().start)),
                        Some("rate_deg"),
                        format!(
                            "{rate} must be finite and non-zero (a zero-rate turn is kind = \"cv\")"
                        ),
                    ));
                }
                PlanarModel::from(CoordinatedTurn::from_degrees_per_second(rate, sa)?)
            }
            (ModelKind::Ct, None) => return Err(missing("rate_deg")),
            (ModelKind::Cv, Some(w)) => {
                return Err(CliError::input(
                    path,
                    Some(line_of(text, w.span().start)),
                    Some("rate_deg"),
                    "a CV model has no turn rate",
                ));
            }
            (ModelKind::Cv, None) => PlanarModel::from(Cv2D::discrete(sa)?),
        };
        built.push(model);
    }
    let n = built.len();
    let markov = e.markov.as_ref().ok_or_else(|| missing("markov"))?;
    check_markov(path, text, markov, n)?;
    let initial = match &e.initial {
        None => vec![1.0 / n as f64; n],
        Some(v) => {
            let mu = v.get_ref();
            let sum: f64 = mu.iter().sum();
            if mu.len() != n
                || mu.iter().any(|p| !(0.0..=1.0).contains(p))
                || (sum - 1.0).abs() > PROBABILITY_SUM_TOL
            {
                return Err(CliError::input(
                    path,
                    Some(line_of(text, v.span().start)),
                    Some("initial"),
                    format!(
                        "needs {n} probabilities (one per model) in [0, 1] summing to 1 (sum = {sum})"
                    ),
                ));
            }
            mu.clone()
        }
    };
    Ok(ImmSpec {
        models: built,
        markov: markov.get_ref().clone(),
        initial,
    })
}

/// Validates the multi-IMM keys `n`, `p`, `clip`, `per_axis` (defaults: the paper's 5,
/// 0.1, 0.05, false).
fn multi_spec(path: &Path, text: &str, e: &EstimatorConfig) -> Result<MultiSpec, CliError> {
    let per_axis = e.per_axis.unwrap_or(false);
    let allowed: &[usize] = if per_axis { &[3, 5] } else { &[3, 5, 7, 9] };
    let n = match &e.n {
        None => 5,
        Some(v) => {
            let n = *v.get_ref();
            match usize::try_from(n) {
                Ok(n) if allowed.contains(&n) => n,
                _ => {
                    return Err(CliError::input(
                        path,
                        Some(line_of(text, v.span().start)),
                        Some("n"),
                        format!(
                            "{n} hypotheses per axis: one of {allowed:?}{}",
                            if per_axis {
                                " with per_axis = true"
                            } else {
                                ""
                            }
                        ),
                    ));
                }
            }
        }
    };
    let p = match &e.p {
        None => 0.1,
        Some(v) => {
            let p = *v.get_ref();
            // The smallest factor 1 − (n − 1)/2 · p must stay positive (eq 14).
            if !(p.is_finite() && p > 0.0 && p * (n as f64 - 1.0) / 2.0 < 1.0) {
                return Err(CliError::input(
                    path,
                    Some(line_of(text, v.span().start)),
                    Some("p"),
                    format!(
                        "{p}: the grid spacing must be positive and keep 1 − (n − 1)/2 · p > 0 (n = {n})"
                    ),
                ));
            }
            p
        }
    };
    let clip = match &e.clip {
        None => Some(0.05),
        Some(v) => {
            let c = *v.get_ref();
            if !(c.is_finite() && (0.0..1.0).contains(&c)) {
                return Err(CliError::input(
                    path,
                    Some(line_of(text, v.span().start)),
                    Some("clip"),
                    format!("{c} must be in [0, 1) (0: no clip)"),
                ));
            }
            (c > 0.0).then_some(c)
        }
    };
    Ok(MultiSpec {
        n,
        p,
        clip,
        per_axis,
    })
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
        EstimatorKind::Imm => Estimator::Imm(imm_spec(path, &text, e)?),
        EstimatorKind::MultiImm => {
            Estimator::MultiImm(imm_spec(path, &text, e)?, multi_spec(path, &text, e)?)
        }
    };
    Ok((sensors, est))
}

/// Runs `argus track` (with a `[tracker]` table: the multi-target tracker, `track_multi.rs`):
/// 2-D plot files with a 2-D CV estimator, 3-D ones (spherical or
/// Cartesian 3-D) with a 3-D CV estimator. Returns the number of track points written.
///
/// # Errors
/// [`CliError::Input`] for bad configuration or plots, filter errors, I/O.
pub(crate) fn run(config: &Path, plots_path: &Path, out: &Path) -> Result<usize, CliError> {
    let (sensors, est) = load(config)?;
    if let Some(multi) = crate::track_multi::load(config, &sensors)? {
        let files = crate::track_multi::Files {
            config,
            plots: plots_path,
            out,
        };
        let plots = plotfile::read(plots_path)?;
        return crate::track_multi::run(&multi, &files, &plots);
    }
    let plots = plotfile::read(plots_path)?;
    let ctx = Ctx {
        config,
        plots_path,
        sensors: &sensors,
    };
    let (rows, n) = if plots.first().is_some_and(|p| p.measurement().dim() == 3) {
        track_3d(&ctx, &est, &plots)?
    } else {
        track_2d(&ctx, &est, &plots)?
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
            .find(|s| s.id == p.sensor())
            .ok_or_else(|| {
                CliError::input(
                    self.plots_path,
                    Some(p.line),
                    Some("sensor"),
                    format!(
                        "unknown sensor {} (not in {})",
                        p.sensor(),
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
    let mut x = init(&z1, &r1, &z2, &r2, p2.time() - p1.time()).map_err(|e| {
        CliError::input(
            ctx.plots_path,
            Some(p2.line),
            Some("t"),
            format!("two-point initialisation: {e}"),
        )
    })?;
    let mut t = p2.time();
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
        x = update(&x, p.time() - t, p)?;
        t = p.time();
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

/// Calls `$f::<R>(args…)` for the run-time mode count `R ∈ 1 … MAX_MODELS`.
macro_rules! by_modes {
    ($r:expr, $f:ident, $($arg:expr),*) => {
        match $r {
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            3 => $f::<3>($($arg),*),
            4 => $f::<4>($($arg),*),
            5 => $f::<5>($($arg),*),
            r => Err(CliError::Usage(format!("{r} IMM models: at most {MAX_MODELS}"))),
        }
    };
}

/// A converter of a 2-D plot to a global Cartesian position and its covariance.
type Convert2<'a> = dyn Fn(&FilePlot) -> Result<(Vector<2>, Matrix<2, 2>), CliError> + 'a;

/// The CSV header of an IMM track file: the state, its variances, `mu_1 … mu_R` and
/// `extra` columns.
fn imm_header(r: usize, extra: &[&str]) -> String {
    let mut cols: Vec<String> = ["t", "track", "x", "vx", "y", "vy"]
        .iter()
        .map(|c| (*c).to_owned())
        .collect();
    cols.extend(["x", "vx", "y", "vy"].iter().map(|n| format!("var_{n}")));
    cols.extend((1..=r).map(|j| format!("mu_{j}")));
    cols.extend(extra.iter().map(|c| (*c).to_owned()));
    let mut h = cols.join(",");
    h.push('\n');
    h
}

/// One IMM track row: time, track id 1, combined state, its variances, then `extra`.
fn imm_row(rows: &mut String, t: f64, g: &Gaussian<4>, extra: &[f64]) {
    use std::fmt::Write as _;
    let _ = write!(rows, "{t},1");
    for v in g.mean().iter() {
        let _ = write!(rows, ",{v}");
    }
    for i in 0..4 {
        let _ = write!(rows, ",{}", g.cov()[(i, i)]);
    }
    for v in extra {
        let _ = write!(rows, ",{v}");
    }
    rows.push('\n');
}

/// The first two plots and the two-point start of an IMM track (every mode from the same
/// Gaussian).
fn imm_start<'p>(
    ctx: &Ctx<'_>,
    plots: &'p [FilePlot],
    convert: &Convert2<'_>,
) -> Result<(Gaussian<4>, &'p FilePlot, &'p [FilePlot]), CliError> {
    let (Some(p1), Some(p2)) = (plots.first(), plots.get(1)) else {
        return Err(CliError::input(
            ctx.plots_path,
            None,
            None,
            "at least two plots are needed to start a track",
        ));
    };
    let (z1, r1) = convert(p1)?;
    let (z2, r2) = convert(p2)?;
    let g = two_point_cv2(&z1, &r1, &z2, &r2, p2.time() - p1.time()).map_err(|e| {
        CliError::input(
            ctx.plots_path,
            Some(p2.line),
            Some("t"),
            format!("two-point initialisation: {e}"),
        )
    })?;
    Ok((g, p2, plots.get(2..).unwrap_or(&[])))
}

fn imm_error(ctx: &Ctx<'_>, p: &FilePlot) -> impl Fn(argus_imm::ImmError) -> CliError {
    let (path, line) = (ctx.plots_path.to_path_buf(), p.line);
    move |e| CliError::input(&path, Some(line), None, format!("IMM update failed: {e}"))
}

/// An IMM with `R` modes over 2-D plots (polar plots converted with the unbiased conversion
/// and the sensor's σ, Cartesian reports as given). Plots of the same instant are applied
/// in turn without mixing or prediction.
fn track_imm<const R: usize>(
    ctx: &Ctx<'_>,
    spec: &ImmSpec,
    plots: &[FilePlot],
    convert: &Convert2<'_>,
) -> Result<(String, usize), CliError> {
    let imm = build_imm::<R>(spec)?;
    let (g, p2, rest) = imm_start(ctx, plots, convert)?;
    let mut est = ImmEstimate::from_common(g, initial_probabilities::<R>(spec))?;
    let mut rows = imm_header(R, &[]);
    let mut t = p2.time();
    imm_row(&mut rows, t, &est.combined()?, &est.mode_probabilities());
    let mut n = 1;
    for p in rest {
        let (z, r) = convert(p)?;
        let meas = position(r)?;
        let dt = p.time() - t;
        let upd = if dt == 0.0 {
            imm.update(&est.into_prediction(), &meas, &z)
        } else {
            imm.step(&est, dt, &meas, &z)
        };
        est = upd.map_err(imm_error(ctx, p))?.estimate;
        t = p.time();
        let c = est.combined().map_err(imm_error(ctx, p))?;
        imm_row(&mut rows, t, &c, &est.mode_probabilities());
        n += 1;
    }
    Ok((rows, n))
}

/// The multi-IMM around an IMM with `R` modes: picks the grid size from `multi`.
fn track_multi<const R: usize>(
    ctx: &Ctx<'_>,
    spec: &ImmSpec,
    multi: MultiSpec,
    plots: &[FilePlot],
    convert: &Convert2<'_>,
) -> Result<(String, usize), CliError> {
    let (p, c) = (multi.p, multi.clip);
    match (multi.per_axis, multi.n) {
        (false, 3) => track_multi_k::<R, 3>(ctx, spec, NoiseGrid::common(p)?, c, plots, convert),
        (false, 5) => track_multi_k::<R, 5>(ctx, spec, NoiseGrid::common(p)?, c, plots, convert),
        (false, 7) => track_multi_k::<R, 7>(ctx, spec, NoiseGrid::common(p)?, c, plots, convert),
        (false, 9) => track_multi_k::<R, 9>(ctx, spec, NoiseGrid::common(p)?, c, plots, convert),
        (true, 3) => {
            track_multi_k::<R, 9>(ctx, spec, NoiseGrid::independent(p)?, c, plots, convert)
        }
        (true, 5) => {
            track_multi_k::<R, 25>(ctx, spec, NoiseGrid::independent(p)?, c, plots, convert)
        }
        (_, n) => Err(CliError::Usage(format!(
            "multi-IMM with n = {n} is not built"
        ))),
    }
}

/// The multi-IMM with `K` noise hypotheses over the polar plots of one sensor; the initial
/// reference is the sensor's configured σ.
fn track_multi_k<const R: usize, const K: usize>(
    ctx: &Ctx<'_>,
    spec: &ImmSpec,
    grid: NoiseGrid<K>,
    clip: Option<f64>,
    plots: &[FilePlot],
    convert: &Convert2<'_>,
) -> Result<(String, usize), CliError> {
    let multi = MultiImm::new(build_imm::<R>(spec)?, grid, clip)?;
    let first = plots.first().ok_or_else(|| {
        CliError::input(
            ctx.plots_path,
            None,
            None,
            "at least two plots are needed to start a track",
        )
    })?;
    let sensor = ctx.sensor(first)?;
    let (sr, sa) = ctx.polar_sigmas(sensor)?;
    let not_polar = |p: &FilePlot, what: &str| {
        CliError::input(
            ctx.plots_path,
            Some(p.line),
            Some("sensor"),
            format!("the multi-IMM estimates one polar radar's noise: {what}"),
        )
    };
    let conv = UnbiasedConversion::<4>::new(0, 2)?.at([sensor.position[0], sensor.position[1]])?;
    let reference = NoiseVariances::from_sigmas(sr, sa).map_err(|e| {
        CliError::input(
            ctx.config,
            None,
            Some("sigma_range"),
            format!("sensor {}: {e}", sensor.id),
        )
    })?;
    let (g, p2, rest) = imm_start(ctx, plots, convert)?;
    let start = ImmEstimate::from_common(g, initial_probabilities::<R>(spec))?;
    let mut est = MultiImmEstimate::<4, R, K>::new(start, reference);
    let mut rows = imm_header(R, &["sigma_range", "sigma_azimuth_deg"]);
    let sig = |v: &NoiseVariances| [v.range().sqrt(), v.azimuth().sqrt().to_degrees()];
    let extra = |est: &MultiImmEstimate<4, R, K>| -> Vec<f64> {
        let mut v = est.mode_probabilities().to_vec();
        v.extend(sig(est.reference()));
        v
    };
    let mut t = p2.time();
    imm_row(&mut rows, t, &est.combined()?, &extra(&est));
    let mut n = 1;
    for p in plots.iter().take(2).chain(rest) {
        if p.sensor() != sensor.id {
            return Err(not_polar(
                p,
                &format!("plot of sensor {} after sensor {}", p.sensor(), sensor.id),
            ));
        }
        let Measurement::Polar(plot) = p.measurement() else {
            return Err(not_polar(p, "a Cartesian report"));
        };
        if p.line <= p2.line {
            continue;
        }
        let dt = p.time() - t;
        est = multi
            .step(&est, dt, plot, &conv)
            .map_err(imm_error(ctx, p))?
            .estimate;
        t = p.time();
        let c = est.combined().map_err(imm_error(ctx, p))?;
        imm_row(&mut rows, t, &c, &extra(&est));
        n += 1;
    }
    Ok((rows, n))
}

/// 2-D plots (polar or Cartesian) with a CV model on `[x, vx, y, vy]`.
fn track_2d(
    ctx: &Ctx<'_>,
    est: &Estimator,
    plots: &[FilePlot],
) -> Result<(String, usize), CliError> {
    let convert = |p: &FilePlot| -> Result<(Vector<2>, Matrix<2, 2>), CliError> {
        let s = ctx.sensor(p)?;
        match p.measurement() {
            Measurement::Cartesian2(c) => Ok((*c.position(), *c.covariance())),
            Measurement::Polar(m) => {
                let (sr, sa) = ctx.polar_sigmas(s)?;
                let (z, r) = unbiased(m.range(), m.azimuth(), sr, sa).map_err(|e| {
                    CliError::input(ctx.plots_path, Some(p.line), Some("range"), e.to_string())
                })?;
                Ok((z + Vector::<2>::new(s.position[0], s.position[1]), r))
            }
            Measurement::Spherical(_) | Measurement::Cartesian3(_) => Err(wrong_dim(ctx, p)),
        }
    };
    match *est {
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
                let post = if let Measurement::Polar(z) = p.measurement() {
                    let s = ctx.sensor(p)?;
                    let (sr, sa) = ctx.polar_sigmas(s)?;
                    let m = polar([s.position[0], s.position[1]], sr, sa)?;
                    step(&f, x, dt, &m, &z.to_vector())
                } else {
                    let (z, r) = convert(p)?;
                    step(&f, x, dt, &position(r)?, &z)
                };
                Ok(post.map_err(ctx.filter_error(p))?.0)
            })
        }
        Estimator::Imm(ref spec) => {
            by_modes!(spec.models.len(), track_imm, ctx, spec, plots, &convert)
        }
        Estimator::MultiImm(ref spec, multi) => {
            by_modes!(
                spec.models.len(),
                track_multi,
                ctx,
                spec,
                multi,
                plots,
                &convert
            )
        }
    }
}

/// 3-D plots (spherical or Cartesian) with a CV model on `[x, vx, y, vy, z, vz]`.
fn track_3d(
    ctx: &Ctx<'_>,
    est: &Estimator,
    plots: &[FilePlot],
) -> Result<(String, usize), CliError> {
    let convert = |p: &FilePlot| -> Result<(Vector<3>, Matrix<3, 3>), CliError> {
        let s = ctx.sensor(p)?;
        match p.measurement() {
            Measurement::Cartesian3(c) => Ok((*c.position(), *c.covariance())),
            Measurement::Spherical(m) => {
                let sig = ctx.spherical_sigmas(s)?;
                let (z, r) =
                    unbiased3(m.range(), m.azimuth(), m.elevation(), sig).map_err(|e| {
                        CliError::input(ctx.plots_path, Some(p.line), Some("range"), e.to_string())
                    })?;
                Ok((z + Vector::<3>::from(s.position), r))
            }
            Measurement::Polar(_) | Measurement::Cartesian2(_) => Err(wrong_dim(ctx, p)),
        }
    };
    match *est {
        Estimator::Imm(_) | Estimator::MultiImm(..) => Err(CliError::input(
            ctx.config,
            None,
            Some("estimator.kind"),
            format!(
                "the IMM estimators track 2-D plots ([x, vx, y, vy]); {} holds 3-D plots",
                ctx.plots_path.display()
            ),
        )),
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
                let post = if let Measurement::Spherical(z) = p.measurement() {
                    let s = ctx.sensor(p)?;
                    let m = spherical(s.position, ctx.spherical_sigmas(s)?)?;
                    step(&f, x, dt, &m, &z.to_vector())
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
