//! The bias-32 Monte Carlo averages accumulated one run at a time, in run order
//! ([`SummarySums`]): per-time sums over the runs, never a run's series, so that averaging
//! any number of runs holds the same numbers. [`Summary::from_runs`] is a fold through
//! it. Each sum adds the same values in the same order as a pass over all the runs would
//! (the scalar series start at −0.0, as `Iterator::sum` does); a series is as long as the
//! shortest run's.

use argus_registration::RegistrationError;

use super::experiment::{RunRecord, Summary, TrackRecord, TrackSummary};

/// Per time, Σ over the runs of a scalar series, and the runs added.
#[derive(Debug, Clone, Default, PartialEq)]
struct Scalars {
    sum: Vec<f64>,
    runs: usize,
}

impl Scalars {
    fn add(&mut self, v: &[f64]) {
        if self.runs == 0 {
            self.sum = vec![-0.0; v.len()];
        }
        self.sum.truncate(v.len());
        for (a, x) in self.sum.iter_mut().zip(v) {
            *a += x;
        }
        self.runs += 1;
    }

    /// `√(Σ / runs)` per time.
    fn rms(&self) -> Vec<f64> {
        let n = self.runs as f64;
        self.sum.iter().map(|s| (s / n).sqrt()).collect()
    }

    /// The mean per time, as the square of [`Scalars::rms`] (as it always was computed).
    fn mean(&self) -> Vec<f64> {
        self.rms().into_iter().map(|x| x * x).collect()
    }
}

/// Per time, Σ over the runs of a four-component series.
#[derive(Debug, Clone, Default, PartialEq)]
struct Quads {
    sum: Vec<[f64; 4]>,
    started: bool,
}

impl Quads {
    fn add(&mut self, v: &[[f64; 4]]) {
        if !self.started {
            self.sum = vec![[0.0; 4]; v.len()];
            self.started = true;
        }
        self.sum.truncate(v.len());
        for (a, x) in self.sum.iter_mut().zip(v) {
            for (o, x) in a.iter_mut().zip(x) {
                *o += x;
            }
        }
    }

    /// `√(Σ / per)` per time and component.
    fn rms(&self, per: f64) -> Vec<[f64; 4]> {
        self.sum
            .iter()
            .map(|a| a.map(|x| (x / per).sqrt()))
            .collect()
    }
}

/// One recorded track's sums (over the runs that recorded it).
#[derive(Debug, Clone, PartialEq)]
struct TrackSums {
    target: usize,
    times: Vec<f64>,
    series: [Scalars; 7],
}

fn track_series(t: &TrackRecord) -> [&Vec<f64>; 7] {
    [
        &t.pos_biased,
        &t.pos_compensated,
        &t.pos_reference,
        &t.vel_biased,
        &t.vel_compensated,
        &t.vel_reference,
        &t.nees_compensated,
    ]
}

/// [`Summary`] accumulated one run at a time.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct SummarySums {
    runs: usize,
    times: Vec<f64>,
    proposed_sq: Quads,
    proposed_var: Quads,
    proposed_nees: Scalars,
    exx_sq: Quads,
    exx_nees: Scalars,
    /// The first run's tracks.
    tracks: Vec<TrackSums>,
}

impl SummarySums {
    /// No run yet.
    #[must_use]
    pub(crate) fn new() -> Self {
        Self::default()
    }

    /// Adds the next run.
    pub(crate) fn add(&mut self, r: &RunRecord) {
        if self.runs == 0 {
            self.times.clone_from(&r.times);
            self.tracks = r
                .tracks
                .iter()
                .map(|t| TrackSums {
                    target: t.target,
                    times: t.times.clone(),
                    series: Default::default(),
                })
                .collect();
        }
        self.runs += 1;
        self.proposed_sq.add(&r.proposed_sq);
        self.proposed_var.add(&r.proposed_var);
        self.proposed_nees.add(&r.proposed_nees);
        self.exx_sq.add(&r.exx_sq);
        self.exx_nees.add(&r.exx_nees);
        for (acc, t) in self.tracks.iter_mut().zip(&r.tracks) {
            for (s, v) in acc.series.iter_mut().zip(track_series(t)) {
                s.add(v);
            }
        }
    }

    /// How many numbers the sums hold (per time and track, whatever the number of runs).
    #[must_use]
    pub(crate) fn retained(&self) -> usize {
        let tracks: usize = self
            .tracks
            .iter()
            .map(|t| 1 + t.times.len() + t.series.iter().map(|s| s.sum.len() + 1).sum::<usize>())
            .sum();
        1 + self.times.len()
            + 4 * (self.proposed_sq.sum.len() + self.proposed_var.sum.len() + self.exx_sq.sum.len())
            + self.proposed_nees.sum.len()
            + self.exx_nees.sum.len()
            + tracks
    }

    /// The averages of the runs added, for a scenario with `sensors` sensors.
    ///
    /// # Errors
    /// [`RegistrationError::Empty`] for no runs or no sensors.
    pub(crate) fn finish(&self, sensors: usize) -> Result<Summary, RegistrationError> {
        if self.runs == 0 {
            return Err(RegistrationError::Empty { what: "run set" });
        }
        if sensors == 0 {
            return Err(RegistrationError::Empty { what: "sensor set" });
        }
        let per = (self.runs * sensors) as f64;
        let tracks = self
            .tracks
            .iter()
            .map(|t| {
                let [pb, pc, pr, vb, vc, vr, nees] = &t.series;
                let mut ts = TrackSummary {
                    target: t.target,
                    pos_biased: pb.rms(),
                    pos_compensated: pc.rms(),
                    pos_reference: pr.rms(),
                    vel_biased: vb.rms(),
                    vel_compensated: vc.rms(),
                    vel_reference: vr.rms(),
                    anees_compensated: nees.mean(),
                    times: t.times.clone(),
                };
                ts.times.truncate(ts.pos_biased.len());
                ts
            })
            .collect();
        let proposed_rmse = self.proposed_sq.rms(per);
        let mut times = self.times.clone();
        times.truncate(proposed_rmse.len());
        Ok(Summary {
            times,
            proposed_rmse,
            proposed_predicted: self.proposed_var.rms(per),
            proposed_anees: self.proposed_nees.mean(),
            exx_rmse: self.exx_sq.rms(per),
            exx_anees: self.exx_nees.mean(),
            tracks,
            runs: self.runs,
            bias_dim: 4 * sensors,
        })
    }
}

impl Summary {
    /// Averages runs of a scenario with `sensors` sensors: a fold through the running sums
    /// of `SummarySums` (the same path as the streamed merge).
    ///
    /// # Errors
    /// [`RegistrationError::Empty`] for no runs or no sensors.
    pub fn from_runs(runs: &[RunRecord], sensors: usize) -> Result<Self, RegistrationError> {
        let mut sums = SummarySums::new();
        for r in runs {
            sums.add(r);
        }
        sums.finish(sensors)
    }
}
