//! A streaming tracking session: time-ordered input events in, values out (see the crate
//! docs, "API for the CLI").

mod error;
mod input;
mod output;

pub use error::SessionError;
pub use input::Input;
pub use output::{Concluded, Output, TrackEvent, TrackSnapshot};

use crate::{Plot, ScanReport, SensorId, Tracker, TrackerConfig, TrackerError};

/// A [`Tracker`] fed in the order its calls must be made: push [`Input`]s in time order,
/// get [`Output`] values back.
///
/// - Plots of one `(time, sensor)` in a row are held and handed to the tracker together:
///   one [`Tracker::process_scan`] for a synchronous sensor (in a configuration with no
///   rotating sensor), one [`Tracker::process`] otherwise.
/// - With a rotating sensor, the tracker is stepped sector by sector before a group of
///   plots at `t` or a marker at `t` ([`Tracker::next_sector_end`],
///   [`Tracker::advance_to`] for every sector ending by `t`), so that each sector's rows
///   show its tracks as it left them.
/// - [`Input::End`] flushes the open sectors ([`Tracker::flush`]).
///
/// Every report becomes an [`Output::Scan`] with one [`TrackSnapshot`] per track it
/// concerns.
///
/// # Errors and what is left
/// A plot the tracker refuses is reported when its group is handed in (by the next
/// plot of another time or sensor, a marker, [`Input::EndOfScan`] or [`Input::End`]),
/// with its tag. The refused group is then dropped (the tracker as before it: it checks
/// every plot first) and the input pushed was not taken; outputs of steps concluded
/// before the error (sectors ended before the group) are in `out`. The session can go on
/// (push that input again to take it).
#[derive(Debug, Clone)]
pub struct Session {
    tracker: Tracker,
    /// Whether some sensor rotates (plots go through [`Tracker::process`]).
    rotating: bool,
    /// The held plots of one `(time, sensor)`, and their tags.
    plots: Vec<Plot>,
    tags: Vec<u64>,
    /// The sensors whose plots were handed in (a rotation is refused from then on).
    started: Vec<SensorId>,
}

impl Session {
    /// A session with a new tracker of `config`.
    ///
    /// # Errors
    /// As [`Tracker::new`].
    pub fn new(config: TrackerConfig) -> Result<Self, TrackerError> {
        let tracker = Tracker::new(config)?;
        Ok(Self {
            rotating: rotating(&tracker),
            tracker,
            plots: Vec::new(),
            tags: Vec::new(),
            started: Vec::new(),
        })
    }

    /// The tracker, to read (its configuration, time, live tracks).
    #[must_use]
    pub fn tracker(&self) -> &Tracker {
        &self.tracker
    }

    /// Takes one input; the scans and sectors it concludes (and, for [`Input::End`], the
    /// end) are appended to `out` in order.
    ///
    /// # Errors
    /// [`SessionError`]: the tracker's error, with the tag of the plot it names (see the
    /// type's docs for what is left).
    pub fn push(&mut self, input: Input, out: &mut Vec<Output>) -> Result<(), SessionError> {
        match input {
            Input::Plot { plot, tag } => {
                if let Some(first) = self.plots.first()
                    && (first.sensor() != plot.sensor()
                        || first.time().total_cmp(&plot.time()).is_ne())
                {
                    self.conclude(out)?;
                }
                self.plots.push(plot);
                self.tags.push(tag);
                Ok(())
            }
            Input::Marker(t) => {
                self.conclude(out)?;
                self.sectors_to(t, out, &[])?;
                let reports = self.tracker.advance_to(t)?;
                self.record(reports, out);
                Ok(())
            }
            Input::Rotation { sensor, rotation } => {
                if self.started.contains(&sensor) || self.plots.iter().any(|p| p.sensor() == sensor)
                {
                    return Err(TrackerError::LateRotation {
                        sensor,
                        reason: "the sensor's first plot was taken",
                    }
                    .into());
                }
                self.tracker.set_rotation(sensor, rotation)?;
                self.rotating = true;
                Ok(())
            }
            Input::EndOfScan => self.conclude(out),
            Input::End => {
                self.conclude(out)?;
                if self.rotating {
                    let reports = self.tracker.flush();
                    self.record(reports, out);
                }
                let end = self
                    .tracker
                    .tracks()
                    .iter()
                    .map(|tr| TrackSnapshot::of(tr, output::last_step(tr)))
                    .collect();
                out.push(Output::End(end));
                Ok(())
            }
        }
    }

    /// Hands the held plots to the tracker; they are dropped on an error too.
    fn conclude(&mut self, out: &mut Vec<Output>) -> Result<(), SessionError> {
        let Some(first) = self.plots.first() else {
            return Ok(());
        };
        let (t, s) = (first.time(), first.sensor());
        let result = self.hand_in(t, s, out);
        if result.is_ok() && !self.started.contains(&s) {
            self.started.push(s);
        }
        self.plots.clear();
        self.tags.clear();
        result
    }

    /// The held plots at `t` of sensor `s`: a rotating configuration's sectors ending by
    /// `t` first, then [`Tracker::process`]; a synchronous one's scan.
    fn hand_in(&mut self, t: f64, s: SensorId, out: &mut Vec<Output>) -> Result<(), SessionError> {
        let tags = std::mem::take(&mut self.tags);
        let result = if self.rotating {
            self.sectors_to(t, out, &tags).and_then(|()| {
                let reports = self
                    .tracker
                    .process(&self.plots)
                    .map_err(|e| SessionError::of(e, &tags))?;
                self.record(reports, out);
                Ok(())
            })
        } else {
            self.tracker
                .process_scan(t, s, &self.plots)
                .map(|report| self.record(std::iter::once(report), out))
                .map_err(|e| SessionError::of(e, &tags))
        };
        self.tags = tags;
        result
    }

    /// Concludes the sectors ending at or before `t`, one [`Tracker::advance_to`] per
    /// sector end (an error is named through `tags`).
    fn sectors_to(
        &mut self,
        t: f64,
        out: &mut Vec<Output>,
        tags: &[u64],
    ) -> Result<(), SessionError> {
        while let Some(end) = self.tracker.next_sector_end()
            && end <= t
        {
            let reports = self
                .tracker
                .advance_to(end)
                .map_err(|e| SessionError::of(e, tags))?;
            self.record(reports, out);
        }
        Ok(())
    }

    /// The outputs of the reports of one tracker call.
    fn record(&mut self, reports: impl IntoIterator<Item = ScanReport>, out: &mut Vec<Output>) {
        for r in reports {
            out.push(Output::Scan(Concluded::new(&mut self.tracker, r)));
        }
    }
}

/// Whether some sensor of the tracker's configuration rotates.
fn rotating(tracker: &Tracker) -> bool {
    tracker
        .config()
        .sensors
        .iter()
        .any(|s| s.rotation.is_some())
}
