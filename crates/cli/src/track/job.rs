//! What `argus track` runs: the configuration file read once ([`super::schema`]), checked
//! once ([`super::spec`]) and turned into a [`Job`]: one estimator over the whole file, or
//! the multi-target tracker when the file has a `[tracker]` table.

use std::path::Path;

use argus_tracker::single::EstimatorSpec;

use super::geo::{self, Reference};
use super::schema::{self, Source};
use super::spec::{self, Sensor};
use super::tracker_config::{self, MultiTarget};
use crate::error::CliError;
use crate::plotfile::FilePlot;

/// A checked `argus track` job.
#[derive(Debug, Clone)]
pub(super) enum Job {
    /// One target: `estimator` over every plot of the file, in order.
    Single {
        sensors: Vec<Sensor>,
        estimator: EstimatorSpec,
    },
    /// The multi-target tracker.
    Multi(MultiTarget),
}

/// A checked job and the configuration's system reference point, if it has one.
#[derive(Debug, Clone)]
pub(super) struct Loaded {
    pub(super) job: Job,
    /// The checked sensors (for an ASTERIX plot file's SAC/SIC).
    pub(super) sensors: Vec<Sensor>,
    pub(super) reference: Option<Reference>,
    /// `(sensor, γ)` of each geodetic site whose own north is not the reference
    /// frame's ([`Sensor::grid_rotation`]).
    pub(super) grid_rotations: Vec<(u32, f64)>,
}

impl Loaded {
    /// `p` in the reference frame ([`geo::to_reference`]).
    pub(super) fn to_reference(&self, p: FilePlot) -> FilePlot {
        geo::to_reference(&self.grid_rotations, p)
    }
}

/// Reads and checks the configuration at `path` ([`load_all`] without the reference).
///
/// # Errors
/// As [`load_all`].
#[cfg(test)]
pub(super) fn load(path: &Path) -> Result<Job, CliError> {
    load_all(path).map(|l| l.job)
}

/// Reads and checks the configuration at `path`. The reference point first (sensors may
/// be given by latitude and longitude around it), then the sensors and the estimator, by
/// the same rules for both jobs; then the `[tracker]` table.
///
/// # Errors
/// [`CliError::Input`] naming the file, the line and the field of the first bad value;
/// [`CliError::Io`]; [`CliError::Motion`] for a model the motion-model crate refuses.
pub(super) fn load_all(path: &Path) -> Result<Loaded, CliError> {
    let (text, file) = schema::read(path)?;
    let src = Source { path, text: &text };
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
