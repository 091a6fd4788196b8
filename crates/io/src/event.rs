//! What a plot file says, as one time-ordered stream of events: the plots, the times a
//! radar's CAT034 messages mark with no plot, and the rotations those messages state.
//! Every reader gives this stream ([`crate::plotfile`]'s plots for the CSV, [`crate::source`]
//! for ASTERIX), and the `argus track` job ([`crate::track`]) turns each event into one
//! [`argus_tracker::Input`] of the tracker's session.

use crate::plotfile::FilePlot;

/// A radar's rotation read from its CAT034 messages.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MessageRotation {
    /// The configured sensor's id.
    pub sensor: u32,
    /// I034/041 (s).
    pub period: f64,
    /// The first north marker's phase in `[0, period)` (s).
    pub north_time: f64,
}

/// One event of a plot file, in the order [`merged`] gives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Event {
    /// A plot, with its line (or ASTERIX record number).
    Plot(FilePlot),
    /// A time (s) a radar's north or sector message marks: time has reached it with no
    /// plot ([`argus_tracker::Input::Marker`]).
    Marker(f64),
    /// A radar's rotation as its messages state it, before any plot
    /// ([`argus_tracker::Input::Rotation`] once the job has given it the configured
    /// direction and the site's grid rotation).
    Rotation(MessageRotation),
}

/// The events of a file's `plots` (in time order), `markers` (in time order) and
/// `rotations`: the rotations first (a radar's rotation holds for its whole file, so the
/// tracker has it before the radar's first plot), then markers and plots by time, a
/// marker before the plots of its time.
#[must_use]
pub fn merged(plots: Vec<FilePlot>, markers: &[f64], rotations: &[MessageRotation]) -> Vec<Event> {
    let mut events = Vec::with_capacity(rotations.len() + markers.len() + plots.len());
    events.extend(rotations.iter().copied().map(Event::Rotation));
    let mut markers = markers.iter().copied().peekable();
    for p in plots {
        while let Some(m) = markers.next_if(|m| *m <= p.time()) {
            events.push(Event::Marker(m));
        }
        events.push(Event::Plot(p));
    }
    events.extend(markers.map(Event::Marker));
    events
}

#[cfg(test)]
mod tests {
    use super::*;
    use argus_sensors::{Plot, SensorId};

    fn plot(t: f64, line: u64) -> FilePlot {
        FilePlot {
            line,
            plot: Plot::polar(t, SensorId(1), 1000.0, 0.5).unwrap(),
        }
    }

    #[test]
    fn rotations_lead_and_markers_precede_the_plots_of_their_time() {
        let r = MessageRotation {
            sensor: 1,
            period: 4.0,
            north_time: 0.5,
        };
        let events = merged(
            vec![plot(1.0, 2), plot(2.0, 3), plot(2.0, 4)],
            &[0.5, 2.0, 3.0, 7.0],
            &[r],
        );
        let kinds: Vec<String> = events
            .iter()
            .map(|e| match e {
                Event::Plot(p) => format!("p{}", p.line),
                Event::Marker(t) => format!("m{t}"),
                Event::Rotation(r) => format!("r{}", r.sensor),
            })
            .collect();
        assert_eq!(kinds, ["r1", "m0.5", "p2", "m2", "p3", "p4", "m3", "m7"]);
    }

    #[test]
    fn no_markers_and_no_rotations_leave_the_plots() {
        let events = merged(vec![plot(1.0, 2), plot(3.0, 3)], &[], &[]);
        assert_eq!(
            events,
            [Event::Plot(plot(1.0, 2)), Event::Plot(plot(3.0, 3))]
        );
    }
}
