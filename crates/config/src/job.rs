//! What `argus track` runs: the configuration file read once ([`crate::schema`]), checked
//! once ([`crate::spec`]) and turned into a [`Job`]: one estimator over the whole file, or
//! the multi-target tracker when the file has a `[tracker]` table.

use std::path::Path;

use crate::error::ConfigError;
use crate::geo::{self, Reference};
use crate::schema::{self, Source};
use argus_tracker::single::EstimatorSpec;

use crate::spec::{self, Sensor};
use crate::tracker_config::{self, MultiTarget};
use argus_sensors::Plot;

/// A checked `argus track` job.
#[derive(Debug, Clone)]
pub enum Job {
    /// One target: `estimator` over every plot of the file, in order.
    Single {
        /// The checked sensors.
        sensors: Vec<Sensor>,
        /// The checked estimator.
        estimator: EstimatorSpec,
    },
    /// The multi-target tracker.
    Multi(MultiTarget),
}

/// A checked job and the configuration's system reference point, if it has one.
#[derive(Debug, Clone)]
pub struct Loaded {
    /// The job.
    pub job: Job,
    /// The checked sensors (for an ASTERIX plot file's SAC/SIC).
    pub sensors: Vec<Sensor>,
    /// The `[reference]` point, when the file has one.
    pub reference: Option<Reference>,
    /// `(sensor, γ)` of each geodetic site whose own north is not the reference
    /// frame's ([`Sensor::grid_rotation`]).
    pub grid_rotations: Vec<(u32, f64)>,
}

impl Loaded {
    /// `p` in the reference frame ([`crate::to_reference`]).
    pub fn to_reference(&self, p: Plot) -> Plot {
        geo::to_reference(&self.grid_rotations, p)
    }
}

/// Reads and checks the configuration at `path`. The reference point first (sensors may
/// be given by latitude and longitude around it), then the sensors and the estimator, by
/// the same rules for both jobs; then the `[tracker]` table.
///
/// # Errors
/// [`ConfigError::Input`] naming the file, the line and the field of the first bad value;
/// [`ConfigError::Io`]; [`ConfigError::Motion`] for a model the motion-model crate refuses.
pub fn load(path: &Path) -> Result<Loaded, ConfigError> {
    let text = std::fs::read_to_string(path).map_err(|e| ConfigError::Io {
        path: path.to_path_buf(),
        source: e,
    })?;
    load_text(&text, path)
}

/// [`load`] on configuration text held in memory; `name` stands for the file's path in
/// errors (`name:LINE: ...`, exactly as a file at `name` would be reported).
///
/// # Errors
/// As [`load`], but never [`ConfigError::Io`].
pub fn load_text(text: &str, name: &Path) -> Result<Loaded, ConfigError> {
    let path = name;
    let file = schema::parse(text, path)?;
    let src = Source { path, text };
    let reference = geo::reference(src, file.reference.as_ref())?;
    let sensors = spec::sensors(src, &file.sensors, reference.as_ref())?;
    let grid_rotations = sensors
        .iter()
        .filter(|s| s.grid_rotation != 0.0)
        .map(|s| (s.id, s.grid_rotation))
        .collect();
    let estimator = spec::estimator(src, &file.estimator)?;
    let all = sensors.clone();
    let job = match &file.tracker {
        None => Job::Single { sensors, estimator },
        Some(table) => Job::Multi(tracker_config::build(
            src, &file, table, &sensors, &estimator,
        )?),
    };
    Ok(Loaded {
        job,
        sensors: all,
        reference,
        grid_rotations,
    })
}
