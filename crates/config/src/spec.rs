//! The checked `[[sensor]]` and `[estimator]` tables: [`Sensor`]s and an [`EstimatorSpec`]
//! with every default filled in (here, once). Both jobs start from these: the
//! single-target estimators use them as they are, the tracker maps them onto its own
//! configuration ([`crate::tracker_config`]).

use argus_asterix::DataSource;
use argus_imm::{AircraftTuning, Augmentation, PROBABILITY_SUM_TOL};
use argus_motion_models::{CoordinatedTurn, Cv2D, PlanarModel};
use argus_tracker::single::{EstimatorSpec, ImmSpec, MAX_MODELS, MultiSpec};
use argus_tracker::{Rotation, RotationDirection};
use toml::Spanned;

use crate::error::ConfigError;
use crate::geo::{self, Reference};
use crate::schema::{
    EstimatorKind, EstimatorTable, Mixing, ModelKind, RotationKind, SensorTable, Source,
};

/// A checked sensor.
#[derive(Debug, Clone, Copy)]
pub struct Sensor {
    /// Its number (the plot file's `sensor` column).
    pub id: u32,
    /// `[x, y, z]` (z = 0 when the config gives two coordinates).
    pub position: [f64; 3],
    /// Range σ (m), azimuth σ (rad).
    pub polar: Option<(f64, f64)>,
    /// Elevation σ (rad).
    pub sigma_elevation: Option<f64>,
    /// A rotating radar's beam (used by the multi-target tracker, whose configuration
    /// checks its values; the single-target estimators take each plot at its time), in
    /// the reference frame: a geodetic site's `north_time` is moved by `γ` (below).
    pub rotation: Option<Rotation>,
    /// Its ASTERIX data source (`sac`, `sic`; default `256 · SAC + SIC = id`).
    pub asterix: Option<argus_asterix::DataSource>,
    /// `γ` (rad): a geodetic site's own east axis from the reference frame's, by which
    /// its plots' azimuths are turned (`geo::sensor_position`); 0 for a sensor
    /// given by `position`.
    pub grid_rotation: f64,
}

fn non_negative(src: Source<'_>, field: &str, v: &Spanned<f64>) -> Result<f64, ConfigError> {
    let x = *v.get_ref();
    if x.is_finite() && x >= 0.0 {
        Ok(x)
    } else {
        Err(src.at(
            v,
            field,
            format!("{x} must be finite and non-negative (a standard deviation)"),
        ))
    }
}

/// Checks the `[[sensor]]` tables: 2 or 3 finite coordinates, σ non-negative, ids distinct.
///
/// # Errors
/// [`ConfigError::Input`] at the bad value.
pub(crate) fn sensors(
    src: Source<'_>,
    tables: &[SensorTable],
    reference: Option<&Reference>,
) -> Result<Vec<Sensor>, ConfigError> {
    let mut sensors: Vec<Sensor> = Vec::with_capacity(tables.len());
    for s in tables {
        let id = *s.id.get_ref();
        let (position, grid_rotation) = match (
            geo::sensor_position(src, s, reference)?,
            &s.position,
        ) {
            (Some(site), _) => site,
            (None, Some(p)) => (xy_position(src, id, p)?, 0.0),
            (None, None) => {
                return Err(src.at(
                    &s.id,
                    "position",
                    format!(
                        "sensor {id}: needs position = [x, y] or latitude, longitude (with a [reference])"
                    ),
                ));
            }
        };
        let polar = match (&s.sigma_range, &s.sigma_azimuth_deg) {
            (Some(r), Some(a)) => Some((
                non_negative(src, "sigma_range", r)?,
                non_negative(src, "sigma_azimuth_deg", a)?.to_radians(),
            )),
            _ => None,
        };
        if sensors.iter().any(|o| o.id == id) {
            return Err(src.missing("id", format!("sensor id {id} given twice")));
        }
        let sigma_elevation = match &s.sigma_elevation_deg {
            Some(e) => Some(non_negative(src, "sigma_elevation_deg", e)?.to_radians()),
            None => None,
        };
        sensors.push(Sensor {
            id,
            position,
            polar,
            sigma_elevation,
            rotation: rotation(src, id, s)?.map(|r| turned(r, grid_rotation)),
            grid_rotation,
            asterix: data_source(src, id, s)?,
        });
    }
    Ok(sensors)
}

/// A `[[sensor]]`'s `sac` and `sic`: both or neither.
///
/// # Errors
/// [`ConfigError::Input`] at the one given without the other.
fn data_source(
    src: Source<'_>,
    id: u32,
    s: &SensorTable,
) -> Result<Option<DataSource>, ConfigError> {
    match (&s.sac, &s.sic) {
        (Some(sac), Some(sic)) => Ok(Some(DataSource {
            sac: *sac.get_ref(),
            sic: *sic.get_ref(),
        })),
        (None, None) => Ok(None),
        (Some(sac), None) => Err(src.at(sac, "sic", format!("sensor {id}: sac needs sic"))),
        (None, Some(sic)) => Err(src.at(sic, "sac", format!("sensor {id}: sic needs sac"))),
    }
}

/// A sensor's `position = [x, y]` or `[x, y, z]` (z = 0 when omitted), finite.
fn xy_position(src: Source<'_>, id: u32, p: &Spanned<Vec<f64>>) -> Result<[f64; 3], ConfigError> {
    let pos = p.get_ref();
    let position = match pos.as_slice() {
        [x, y] => [*x, *y, 0.0],
        [x, y, z] => [*x, *y, *z],
        _ => {
            return Err(src.at(
                p,
                "position",
                format!(
                    "sensor {id}: position needs 2 or 3 coordinates, not {}",
                    pos.len()
                ),
            ));
        }
    };
    if !position.iter().all(|v| v.is_finite()) {
        return Err(src.at(
            p,
            "position",
            format!("sensor {id}: position must be finite"),
        ));
    }
    Ok(position)
}

/// A sensor's `revolution_period`, `rotation` (default clockwise) and `north_time`
/// (default 0): the last two need the first.
fn rotation(src: Source<'_>, id: u32, s: &SensorTable) -> Result<Option<Rotation>, ConfigError> {
    let Some(period) = &s.revolution_period else {
        if let Some(r) = &s.rotation {
            return Err(src.at(
                r,
                "rotation",
                format!("sensor {id}: needs revolution_period"),
            ));
        }
        if let Some(n) = &s.north_time {
            return Err(src.at(
                n,
                "north_time",
                format!("sensor {id}: needs revolution_period"),
            ));
        }
        return Ok(None);
    };
    let direction = match s.rotation.as_ref().map(|r| *r.get_ref()) {
        None | Some(RotationKind::Clockwise) => RotationDirection::Clockwise,
        Some(RotationKind::Counterclockwise) => RotationDirection::Counterclockwise,
    };
    Ok(Some(Rotation {
        period: *period.get_ref(),
        direction,
        north_time: s.north_time.as_ref().map_or(0.0, |n| *n.get_ref()),
    }))
}

/// The beam of a site whose east axis is `γ` from the reference frame's: it points at
/// the site's north, the reference frame's azimuth `π/2 + γ`, at `north_time`, so in the
/// reference frame it points at `π/2` when it has turned by `−γ` more (clockwise: at
/// `north_time + γ P / 2π`; counter-clockwise: `north_time − γ P / 2π`).
pub fn turned(r: Rotation, gamma: f64) -> Rotation {
    let shift = gamma * r.period / std::f64::consts::TAU;
    let north_time = match r.direction {
        RotationDirection::Clockwise => r.north_time + shift,
        RotationDirection::Counterclockwise => r.north_time - shift,
    };
    Rotation { north_time, ..r }
}

/// Checks `[estimator]` and fills in its defaults.
///
/// # Errors
/// [`ConfigError::Input`] at the bad value, or naming the missing key;
/// [`ConfigError::Motion`] for a model the motion-model crate refuses.
pub(crate) fn estimator(src: Source<'_>, e: &EstimatorTable) -> Result<EstimatorSpec, ConfigError> {
    let kind = *e.kind.get_ref();
    let sigma_a = || {
        let sa = e
            .sigma_a
            .as_ref()
            .ok_or_else(|| missing(src, kind, "sigma_a"))?;
        non_negative(src, "sigma_a", sa)
    };
    Ok(match kind {
        EstimatorKind::KfConverted => EstimatorSpec::KfConverted(sigma_a()?),
        EstimatorKind::Ekf => EstimatorSpec::Ekf(sigma_a()?),
        EstimatorKind::Imm => EstimatorSpec::Imm(imm_spec(src, e)?),
        EstimatorKind::MultiImm => EstimatorSpec::MultiImm(imm_spec(src, e)?, multi_spec(src, e)?),
        EstimatorKind::AircraftImm => EstimatorSpec::Aircraft(aircraft(src, e)?),
    })
}

/// A key that `kind` needs is not written.
fn missing(src: Source<'_>, kind: EstimatorKind, key: &str) -> ConfigError {
    src.missing(key, format!("required by estimator kind {kind:?}"))
}

/// Checks the Markov matrix: square, one row per model, entries in [0, 1], rows summing
/// to 1 within 1e-9.
fn check_markov(src: Source<'_>, m: &Spanned<Vec<Vec<f64>>>, n: usize) -> Result<(), ConfigError> {
    let rows = m.get_ref();
    if rows.len() != n || rows.iter().any(|r| r.len() != n) {
        return Err(src.at(
            m,
            "markov",
            format!("must be {n} × {n} (one row and column per model)"),
        ));
    }
    for (i, r) in rows.iter().enumerate() {
        let sum: f64 = r.iter().sum();
        if r.iter().any(|p| !(0.0..=1.0).contains(p)) || (sum - 1.0).abs() > 1e-9 {
            return Err(src.at(
                m,
                "markov",
                format!(
                    "row {} is not stochastic (entries in [0, 1] summing to 1; sum = {sum})",
                    i + 1
                ),
            ));
        }
    }
    Ok(())
}

/// One IMM mode's motion model.
fn model(
    src: Source<'_>,
    kind: EstimatorKind,
    m: &crate::schema::ModelTable,
) -> Result<PlanarModel, ConfigError> {
    let sa = non_negative(src, "sigma_a", &m.sigma_a)?;
    Ok(match (m.kind, &m.rate_deg) {
        (ModelKind::Ct, Some(w)) => {
            let rate = *w.get_ref();
            if !(rate.is_finite() && rate != 0.0) {
                return Err(src.at(
                    w,
                    "rate_deg",
                    format!(
                        "{rate} must be finite and non-zero (a zero-rate turn is kind = \"cv\")"
                    ),
                ));
            }
            PlanarModel::from(CoordinatedTurn::from_degrees_per_second(rate, sa)?)
        }
        (ModelKind::Ct, None) => return Err(missing(src, kind, "rate_deg")),
        (ModelKind::Cv, Some(w)) => {
            return Err(src.at(w, "rate_deg", "a CV model has no turn rate"));
        }
        (ModelKind::Cv, None) => PlanarModel::from(Cv2D::discrete(sa)?),
    })
}

/// Checks the IMM keys (`models`, `markov`, `initial`, default: uniform) and builds the
/// motion models.
fn imm_spec(src: Source<'_>, e: &EstimatorTable) -> Result<ImmSpec, ConfigError> {
    let kind = *e.kind.get_ref();
    let models = e
        .models
        .as_ref()
        .ok_or_else(|| missing(src, kind, "models"))?
        .get_ref();
    if models.is_empty() || models.len() > MAX_MODELS {
        return Err(src.missing(
            "models",
            format!("1 to {MAX_MODELS} models, not {}", models.len()),
        ));
    }
    let built = models
        .iter()
        .map(|m| model(src, kind, m))
        .collect::<Result<Vec<_>, _>>()?;
    let n = built.len();
    let markov = e
        .markov
        .as_ref()
        .ok_or_else(|| missing(src, kind, "markov"))?;
    check_markov(src, markov, n)?;
    let initial = match &e.initial {
        None => vec![1.0 / n as f64; n],
        Some(v) => check_initial(src, v, n)?.to_vec(),
    };
    Ok(ImmSpec {
        models: built,
        markov: markov.get_ref().clone(),
        initial,
    })
}

/// Checks `initial`: `n` probabilities in [0, 1] summing to 1 (within 1e-9).
fn check_initial<'v>(
    src: Source<'_>,
    v: &'v Spanned<Vec<f64>>,
    n: usize,
) -> Result<&'v [f64], ConfigError> {
    let mu = v.get_ref();
    let sum: f64 = mu.iter().sum();
    if mu.len() != n
        || mu.iter().any(|p| !(0.0..=1.0).contains(p))
        || (sum - 1.0).abs() > PROBABILITY_SUM_TOL
    {
        return Err(src.at(
            v,
            "initial",
            format!("needs {n} probabilities (one per model) in [0, 1] summing to 1 (sum = {sum})"),
        ));
    }
    Ok(mu)
}

/// A standard deviation that must be finite and positive (`to_rad`: given in degrees).
fn positive(
    src: Source<'_>,
    field: &str,
    v: &Spanned<f64>,
    to_rad: bool,
) -> Result<f64, ConfigError> {
    let x = *v.get_ref();
    if x.is_finite() && x > 0.0 {
        Ok(if to_rad { x.to_radians() } else { x })
    } else {
        Err(src.at(v, field, format!("{x} must be finite and positive")))
    }
}

/// Checks the aircraft IMM's keys over `AircraftTuning::<2, 3>::default()`: every key is
/// optional and replaces its default (degrees in the file, radians in the tuning).
fn aircraft(src: Source<'_>, e: &EstimatorTable) -> Result<AircraftTuning<2, 3>, ConfigError> {
    for (v, key) in [
        (e.sigma_a.as_ref().map(Spanned::span), "sigma_a"),
        (e.models.as_ref().map(Spanned::span), "models"),
    ] {
        if let Some(span) = v {
            return Err(ConfigError::input(
                src.path,
                Some(src.line(&span)),
                Some(key),
                "not used by kind \"aircraft-imm\" (its modes are set by cv_sigma_a, ct_sigma_a, ct_sigma_omega_deg)",
            ));
        }
    }
    let mut t = AircraftTuning::<2, 3>::default();
    if let Some(v) = &e.cv_sigma_a {
        let [low, high] = v.get_ref().as_slice() else {
            return Err(src.at(
                v,
                "cv_sigma_a",
                format!(
                    "needs 2 values (the two CV modes), not {}",
                    v.get_ref().len()
                ),
            ));
        };
        if ![low, high].iter().all(|x| x.is_finite() && **x > 0.0) {
            return Err(src.at(v, "cv_sigma_a", "values must be finite and positive (m/s²)"));
        }
        t.cv_sigma_a = [*low, *high];
    }
    if let Some(v) = &e.ct_sigma_a {
        t.ct_sigma_a = positive(src, "ct_sigma_a", v, false)?;
    }
    if let Some(v) = &e.ct_sigma_omega_deg {
        t.ct_sigma_omega = positive(src, "ct_sigma_omega_deg", v, true)?;
    }
    if let Some(v) = &e.start_sigma_omega_deg {
        t.start_sigma_omega = positive(src, "start_sigma_omega_deg", v, true)?;
    }
    if let Some(m) = &e.markov {
        check_markov(src, m, 3)?;
        for (row, r) in t.markov.iter_mut().zip(m.get_ref()) {
            row.copy_from_slice(r);
        }
    }
    if let Some(v) = &e.initial {
        t.start_mu.copy_from_slice(check_initial(src, v, 3)?);
    }
    let fixed = e
        .mixing
        .as_ref()
        .is_some_and(|m| *m.get_ref() == Mixing::Fixed);
    t.augmentation = match (&e.mixing_sigma_omega_deg, fixed) {
        (Some(v), true) => Augmentation::Fixed {
            sigma: positive(src, "mixing_sigma_omega_deg", v, true)?,
        },
        (None, true) => {
            return Err(src.missing("mixing_sigma_omega_deg", "required by mixing = \"fixed\""));
        }
        (Some(v), false) => {
            return Err(src.at(
                v,
                "mixing_sigma_omega_deg",
                "used by mixing = \"fixed\" only",
            ));
        }
        (None, false) => Augmentation::Unbiased,
    };
    Ok(t)
}

/// Checks the multi-IMM keys `n`, `p`, `clip`, `per_axis` (defaults:
/// [`MultiSpec::DEFAULT`]).
fn multi_spec(src: Source<'_>, e: &EstimatorTable) -> Result<MultiSpec, ConfigError> {
    let d = MultiSpec::DEFAULT;
    let per_axis = e.per_axis.as_ref().map_or(d.per_axis, |v| *v.get_ref());
    let allowed: &[usize] = if per_axis { &[3, 5] } else { &[3, 5, 7, 9] };
    let n = match &e.n {
        None => d.n,
        Some(v) => {
            let n = *v.get_ref();
            match usize::try_from(n) {
                Ok(n) if allowed.contains(&n) => n,
                _ => {
                    let with = if per_axis {
                        " with per_axis = true"
                    } else {
                        ""
                    };
                    return Err(src.at(
                        v,
                        "n",
                        format!("{n} hypotheses per axis: one of {allowed:?}{with}"),
                    ));
                }
            }
        }
    };
    let p = match &e.p {
        None => d.p,
        Some(v) => {
            let p = *v.get_ref();
            // The smallest factor 1 − (n − 1)/2 · p must stay positive (eq 14).
            if !(p.is_finite() && p > 0.0 && p * (n as f64 - 1.0) / 2.0 < 1.0) {
                return Err(src.at(
                    v,
                    "p",
                    format!(
                        "{p}: the grid spacing must be positive and keep 1 − (n − 1)/2 · p > 0 (n = {n})"
                    ),
                ));
            }
            p
        }
    };
    let clip = match &e.clip {
        None => d.clip,
        Some(v) => {
            let c = *v.get_ref();
            if !(c.is_finite() && (0.0..1.0).contains(&c)) {
                return Err(src.at(v, "clip", format!("{c} must be in [0, 1) (0: no clip)")));
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
