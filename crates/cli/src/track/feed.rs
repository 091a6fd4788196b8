//! The multi-target tracker fed plots one at a time in file order: plots of one
//! `(time, sensor)` are handed in together (one scan of a synchronous sensor, one
//! [`Tracker::process`] call for a rotating one), a rotating radar is stepped sector by
//! sector ([`Tracker::next_sector_end`], [`Tracker::advance_to`]) so that each sector's
//! rows show its tracks as it left them, and every report goes to the [`Tally`]. Nothing
//! is kept but the plots of the current `(time, sensor)`, so a file of any length is
//! tracked in the memory of its busiest instant.

use argus_io::plotfile::FilePlot;
use argus_tracker::{Plot, Tracker, TrackerConfig, TrackerError};

use super::multi_files::{Files, plot_error, tracker_plot};
use super::tally::Tally;
use crate::error::CliError;

/// The plots of the current `(time, sensor)` and their file lines.
pub(super) struct Feed {
    rotating: bool,
    plots: Vec<Plot>,
    lines: Vec<u64>,
}

impl Feed {
    /// A feed for the tracker of `config` (rotating when any sensor rotates).
    pub(super) fn new(config: &TrackerConfig) -> Self {
        Self {
            rotating: config.sensors.iter().any(|s| s.rotation.is_some()),
            plots: Vec::new(),
            lines: Vec::new(),
        }
    }

    /// Takes the next file plot: a plot at a new time or of another sensor first hands
    /// the held ones to the tracker.
    ///
    /// # Errors
    /// [`CliError::Input`] naming the plot's line for a plot the tracker refuses.
    pub(super) fn push(
        &mut self,
        tracker: &mut Tracker,
        tally: &mut Tally<'_>,
        files: &Files<'_>,
        p: &FilePlot,
    ) -> Result<(), CliError> {
        let plot = tracker_plot(files, p)?;
        if let Some(first) = self.plots.first()
            && (first.sensor() != plot.sensor() || first.time().total_cmp(&plot.time()).is_ne())
        {
            self.conclude(tracker, tally, files)?;
        }
        self.plots.push(plot);
        self.lines.push(p.line);
        Ok(())
    }

    /// Hands the held plots to the tracker (a scan, or plots of a rotating sensor, whose
    /// sector the tracker concludes when the beam has passed it).
    ///
    /// # Errors
    /// As [`Self::push`].
    pub(super) fn conclude(
        &mut self,
        tracker: &mut Tracker,
        tally: &mut Tally<'_>,
        files: &Files<'_>,
    ) -> Result<(), CliError> {
        let Some(first) = self.plots.first() else {
            return Ok(());
        };
        let (t, s) = (first.time(), first.sensor());
        let at = |lines: &[u64], e: TrackerError| plot_error(files, lines, e);
        if self.rotating {
            while let Some(end) = tracker.next_sector_end()
                && end <= t
            {
                let reports = tracker.advance_to(end).map_err(|e| at(&self.lines, e))?;
                for r in &reports {
                    tally.record(tracker, r);
                }
            }
            let reports = tracker
                .process(&self.plots)
                .map_err(|e| at(&self.lines, e))?;
            for r in &reports {
                tally.record(tracker, r);
            }
        } else {
            let report = tracker
                .process_scan(t, s, &self.plots)
                .map_err(|e| at(&self.lines, e))?;
            tally.record(tracker, &report);
        }
        self.plots.clear();
        self.lines.clear();
        Ok(())
    }

    /// Time has reached `t` with no plot (an ASTERIX CAT034 message, [`super::source`]):
    /// the held plots handed in, the sectors ended by `t` concluded, then
    /// [`Tracker::advance_to`] `t`.
    ///
    /// # Errors
    /// [`CliError::Input`] for a time the tracker refuses (before one it processed).
    pub(super) fn advance(
        &mut self,
        tracker: &mut Tracker,
        tally: &mut Tally<'_>,
        files: &Files<'_>,
        t: f64,
    ) -> Result<(), CliError> {
        self.conclude(tracker, tally, files)?;
        let at = |e: TrackerError| plot_error(files, &[], e);
        while let Some(end) = tracker.next_sector_end()
            && end <= t
        {
            for r in &tracker.advance_to(end).map_err(at)? {
                tally.record(tracker, r);
            }
        }
        for r in &tracker.advance_to(t).map_err(at)? {
            tally.record(tracker, r);
        }
        Ok(())
    }

    /// The end of the plots: the held ones handed in and, with a rotating sensor, the
    /// open sectors concluded ([`Tracker::flush`]).
    ///
    /// # Errors
    /// As [`Self::push`].
    pub(super) fn finish(
        &mut self,
        tracker: &mut Tracker,
        tally: &mut Tally<'_>,
        files: &Files<'_>,
    ) -> Result<(), CliError> {
        self.conclude(tracker, tally, files)?;
        if self.rotating {
            for r in &tracker.flush() {
                tally.record(tracker, r);
            }
        }
        Ok(())
    }
}
