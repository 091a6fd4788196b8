//! What a [`super::Session`] is fed.

use crate::{Plot, Rotation, SensorId};

/// One input event of a [`super::Session`], in time order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Input {
    /// A plot, with the caller's tag for it (e.g. its file line), by which an error about
    /// it is named ([`super::SessionError::tag`]). Plots of one `(time, sensor)` in a row
    /// are handed to the tracker together (one scan of a synchronous sensor) when a plot
    /// of another time or sensor, a marker, [`Input::EndOfScan`] or [`Input::End`]
    /// follows.
    Plot {
        /// The plot.
        plot: Plot,
        /// The caller's tag.
        tag: u64,
    },
    /// Time has reached this time (s) with no plot (e.g. an ASTERIX CAT034 north or
    /// sector message): the sectors of rotating sensors ending by then are concluded, and
    /// later plots must not precede it ([`crate::Tracker::advance_to`]).
    Marker(f64),
    /// A sensor's rotation learnt from the stream (e.g. from CAT034): the sensor becomes a
    /// rotating radar (or its rotation is replaced) as if configured so. Only before the
    /// sensor's first plot: later it is refused
    /// ([`crate::TrackerError::LateRotation`]; the session is unchanged), since its
    /// sectors are then laid out.
    Rotation {
        /// The sensor.
        sensor: SensorId,
        /// Its rotation.
        rotation: Rotation,
    },
    /// The plots held are a whole scan: hand them to the tracker now (for a caller that
    /// feeds a stream in batches and knows a batch ends on a scan). A rotating sensor's
    /// sector stays open until later plots, a marker or [`Input::End`] pass its end.
    EndOfScan,
    /// The end of the stream: the plots held handed in and, with a rotating sensor, the
    /// open sectors concluded up to the latest time seen ([`crate::Tracker::flush`]);
    /// then [`super::Output::End`]. More inputs may follow (the sectors stay open, as
    /// after a flush).
    End,
}
