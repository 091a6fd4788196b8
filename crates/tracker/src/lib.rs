//! Multi-target surveillance tracker: plots in, tracks out (and the single-target engine,
//! [`single`]).
//!
//! A [`Tracker`] consumes a time-ordered stream of 2-D [`Plot`]s (the workspace's plot
//! type from `argus-sensors`, re-exported here with its [`SensorId`]) from one or more
//! sensors ([`SensorConfig`]: id, position, polar noise), scan by scan: Cartesian plots
//! ([`Plot::cartesian`], a position with its covariance) or polar plots
//! ([`Plot::polar`], range and azimuth from the sensor's position). It maintains many
//! [`Track`]s, each with its own estimator on the constant-velocity state
//! `[x, vx, y, vy]`, chosen by [`TrackerConfig::estimator`]: a Kalman filter
//! ([`argus_filters::Kf`] on [`argus_motion_models::Cv2D`]), an EKF updated with the
//! polar plots themselves ([`argus_filters::Ekf`], [`argus_sensors::Polar2D`]), a two-mode
//! CV IMM ([`argus_imm::Imm`]), seed 000's multi-IMM measurement-noise estimator
//! ([`argus_imm::MultiImm`], its `R` estimate on [`EstimatorState::noise_estimate`]), or the
//! aircraft IMM ([`argus_imm::AircraftImm`]: two CV modes and a coordinated turn with the
//! turn rate as a state, its estimate on [`EstimatorState::turn_rate`]; each track's
//! estimator state is [`Track::state`]).
//!
//! Polar plots are converted once per scan by the unbiased conversion
//! ([`argus_sensors::convert_polar`], Mo Longbin et al. 1998) plus the sensor position:
//! that Cartesian plot is what the grid bins, the gates of KF and IMM tracks see, the
//! initiation pairs and the KF and IMM update. The EKF gates and updates in `(r, θ)` with
//! its own `S` (its query box is widened to hold that gate: see `polar_half`), and its
//! likelihoods are divided by the Jacobian `r` of the polar map so that they are per m²
//! like the clutter density. The multi-IMM gates on the plot converted with the
//! configured noise and updates each of its IMMs with the plot converted with that IMM's
//! hypothesis. The aircraft IMM gates in `(r, θ)` per mode (a plot in any mode's gate,
//! at its smallest normalised distance; likelihood `Σⱼ μ̄ⱼ N(νⱼ; 0, Sⱼ) / r`) and updates
//! every mode with the polar plot itself; its tracks start from the initiation's
//! two-point estimate with the CT mode's turn-rate prior.
//!
//! # One scan
//! 1. Every live track is predicted to the scan time.
//! 2. **Gating at scale.** The scan's plots are binned in a square grid (cell
//!    [`TrackerConfig::grid_cell`]); each track looks only at the cells met by the
//!    bounding box of its gate, `±√(γ (P_xx + R_max,xx))` per axis, then applies the
//!    chi-square gate `νᵀ S⁻¹ ν ≤ γ` (`γ` from [`TrackerConfig::gate_probability`],
//!    [`argus_association::Gate`]) with `S` from
//!    [`argus_filters::MeasurementPrediction`]. The cost is tracks × plots near each
//!    track, not tracks × all plots.
//! 3. **GNN.** Gated pairs form a bipartite graph whose connected components
//!    (clusters) are solved one by one (clusters of more than 64 tracks, which chains of
//!    large initiation gates can form in dense clutter, greedily by increasing cost —
//!    an approximation) by an optimal 2-D assignment minimising the sum
//!    of normalised distances `νᵀ S⁻¹ ν`, a track staying unassigned at cost `γ`.
//!    Confirmed tracks are served first, tentative ones take the plots left.
//!    **JPDA** ([`AssociationConfig::Jpda`]) may replace GNN for confirmed tracks: per
//!    cluster, exact joint events when there are at most `max_exact_events`, Fitzgerald's
//!    cheap JPDA (`β_tj = G_tj / (S_t + S^j − G_tj + B)`) beyond.
//!    **IMM-JPDA** (JPDA with [`EstimatorConfig::ImmCv2`]): a plot is gated when it is in
//!    some mode's gate (the query box holds every mode's), its likelihood is the mode
//!    mixture `Σ_r μ̄_r N(ν_r; 0, S_r)`, the JPDA weights come from those, and each mode is
//!    updated with its own PDA mixture, weights `P(r, j) / μ_r` with
//!    `P(r, j) = β_j μ̄_r N_r,j / N_j`, `P(r, 0) = β₀ μ̄_r`; the mode probabilities are
//!    `μ_r = μ̄_r (β₀ + Σ_j β_j N_r,j / N_j)`, the mode likelihood summed over the plot
//!    events (Blom & Bloem, IEEE Trans. AC 45(2), 2000; Bar-Shalom, Willett & Tian,
//!    *Tracking and Data Fusion*, 2011). With identical modes it is JPDA with the KF.
//!    The aircraft IMM ([`EstimatorConfig::Aircraft`]) does the same with its three
//!    modes' polar EKF updates and the `(r, θ)` mixture likelihood per m².
//!    The solver is the [`lsap`] crate: SciPy's `linear_sum_assignment` algorithm
//!    (Crouse's shortest augmenting path form of Jonker–Volgenant) on `f64` costs and
//!    rectangular matrices. `pathfinding::kuhn_munkres`, the best-known Rust solver,
//!    needs `Ord` (integer) weights and documents that it does not support floats;
//!    `lapjv` needs square `ndarray` matrices. lsap rejects infinite costs, so pairs
//!    outside the gate get a prohibitive finite cost and are filtered out afterwards.
//! 4. **Track management.** Assigned tracks are updated, the others keep their
//!    prediction. A tentative track is confirmed when it has
//!    [`TrackerConfig::confirm_m`] hits in its first [`TrackerConfig::confirm_n`]
//!    opportunities (its two initiating plots are the first two), and deleted as soon
//!    as that can no longer happen. A confirmed track is deleted after
//!    [`TrackerConfig::max_misses`] consecutive misses. Any track is deleted when its
//!    worst position standard deviation exceeds [`TrackerConfig::max_position_sigma`]
//!    or its filter step fails. Ids are never reused. With
//!    [`TrackerConfig::score`] set, confirmation and deletion follow the track score
//!    (log-likelihood ratio, SPRT) instead of M-of-N: see [`ScoreConfig`].
//! 5. **Initiation.** Plots used by no track are paired with unused plots of earlier
//!    scans (at most [`TrackerConfig::max_initiation_interval`] old) through the
//!    velocity gate `‖z₂ − z₁‖ ≤ v_max Δt + k √tr(R₁ + R₂)` (GNN again, on the
//!    normalised distance), and each pair starts a tentative track by two-point
//!    differencing ([`argus_filters::two_point_cv2`]). Plots still unused wait as
//!    first points.
//!
//! # One sector (rotating radars)
//! A sensor with a [`Rotation`] ([`SensorConfig::with_rotation`]) is a rotating radar:
//! its beam's azimuth is `β(t) = π/2 ∓ 2π (t − north_time) / period` (Argus's azimuth,
//! counter-clockwise from east; − clockwise), and each plot has its own time, the time
//! the beam crossed what it saw. Its plots are not scans: [`Tracker::process`] buffers
//! them into **sectors**, time windows of [`TrackerConfig::sector_fraction`] × period
//! aligned to `north_time` (`[north_time + k L, north_time + (k + 1) L)`), and processes
//! a sector when a plot (of any sensor) at or after its end arrives, or on
//! [`Tracker::advance_to`] (time passed with no plot, e.g. a sector or north marker)
//! and [`Tracker::flush`] (the end of a stream: up to the last time seen). Sectors in
//! which nothing can happen (no plot, no track swept) are skipped without a report.
//! 1. **Which tracks.** For each live track the beam's crossing time `t_c` of its
//!    azimuth (extrapolated on its mean velocity, refined twice) and the half-time
//!    `τ` the beam takes to sweep its gate (the gate's bounding circle
//!    `√(γ (tr P_pos(t_c) + R))` seen from the radar, `R` the larger of the sector's
//!    plots' and the radar's noise at that range). A track takes part in the sector when
//!    the sweep starts before the sector's end, `t_c − τ < t_end`, and it has had no
//!    opportunity from this radar in the last half revolution (so at most one per
//!    revolution: once updated or missed, it waits until the beam comes round).
//! 2. **Gating and association** as in a scan (steps 2–3 below): one global GNN (or
//!    JPDA) over the sector's plots and those tracks, each predicted to its own `t_c`.
//! 3. **Update, miss or carry.** A track assigned a plot is predicted to the plot's own
//!    time and updated with it (JPDA: its mixture at `t_c`). A track with no plot
//!    **misses only when the beam has left its gate within the sector**
//!    (`t_c + τ < t_end`), never because of another target's plot; otherwise its gate
//!    straddles the sector's end and it is carried to the next sector untouched.
//!    Confirmation and deletion count these opportunities as a scan counts its own.
//! 4. **Initiation** pairs the unused plots with unused plots at least half a
//!    revolution older (from an earlier revolution), each at its own time in the
//!    velocity gate; the new track's time is its second plot's.
//!
//! **Several radars.** Plots of several sensors, rotating or not, interleave in one
//! time-ordered stream. Before a plot at `t` is taken, every sector (of any rotating
//! sensor) ending at or before `t` is processed, in order of their ends; a synchronous
//! sensor's plots form their scan at `t` after that. A sector is therefore processed
//! only when every plot before its end has arrived. Sectors of two radars overlap in
//! time, so a track updated by radar A's sector at `t_a` may be offered a plot of radar
//! B's later-ending sector taken before `t_a`: a track is never predicted backwards, such
//! a plot updates it at its own time `t_a` (a lag of at most one sector of B; sectors of
//! 1/8 revolution keep it under 0.7 s for a 5-s radar). Each sector yields a
//! [`ScanReport`] with its span (`start`, `time`), its sensor, and the tracks it
//! `visited` (updated or missed).
//!
//! The densities of [`ScoreConfig`] and [`AssociationConfig::Jpda`] are per scan: for a
//! rotating radar, per revolution (a track has one opportunity per revolution). A target
//! that passes over the radar, whose azimuth turns by about π between two sweeps, can be
//! swept twice within half a revolution: the second is not an opportunity (one row less).
//! Cost: each sector computes the beam crossing only of the tracks that may be due (a
//! track remembers, per rotating sensor, until when no sector sweeps its gate, as long as
//! its estimate is unchanged); the rest is the scan's work on the sector's plots and
//! those tracks (`tracker_sector_step` in `docs/BENCHMARKS.md`).
//!
//! Rotating sensors are not built with the multi-IMM estimator (refused by the
//! configuration), and their plots do not go through [`Tracker::process_scan`].
//!
//! # Bad input
//! A plot with a non-finite value, a negative range or a covariance that is not symmetric
//! positive definite cannot be built ([`Plot`]'s constructors refuse it). Plots out of
//! time order, from a sensor not in the configuration, polar plots with a zero range or
//! from a sensor without polar noise, 3-D plots, Cartesian plots for the multi-IMM or the
//! aircraft IMM, and
//! bad configurations give a
//! [`TrackerError`] that names the plot (index, time, sensor) or the field. All plots are checked before any track is touched, so
//! a rejected call leaves the tracker unchanged. A track whose filter step fails
//! numerically is deleted alone.
//!
//! # API for the CLI
//! Build a [`TrackerConfig`] (public fields, validated by [`Tracker::new`]) and drive a
//! [`Session`] with time-ordered [`Input`] events: plots, each with the caller's tag
//! (e.g. its file line), marker times (time passes with no plot: an ASTERIX CAT034 north
//! or sector message), rotations learnt from the stream (before the sensor's first plot;
//! refused later, [`TrackerError::LateRotation`]), [`Input::EndOfScan`] and
//! [`Input::End`]. The session owns the order of the tracker's calls: plots of one
//! `(time, sensor)` handed in together, rotating radars stepped sector by sector, markers
//! advanced to, the end flushed. It gives back [`Output`] values: per concluded scan or
//! sector a [`Concluded`] (the [`ScanReport`]: sensor, sector or scan, span, plots
//! assigned, ids initiated, confirmed, deleted; and one [`TrackSnapshot`] per track it
//! concerns, in id order, with its estimate, [`EstimatorState`], score, status, deletion
//! reason, [`TrackEvent`] and the plot that updated it), and at the end the live tracks.
//! An error ([`SessionError`]) carries the tag of the plot it is about. This is what
//! `argus track --config` writes its tracks CSV and summary from.
//!
//! The [`Tracker`] itself stays public for callers that want its steps: [`Tracker::process`]
//! (a stream; consecutive plots of one time and synchronous sensor form a scan, a
//! rotating sensor's go into its sectors), [`Tracker::process_scan`] (one synchronous
//! scan, possibly empty), and with rotating sensors [`Tracker::advance_to`],
//! [`Tracker::flush`] and [`Tracker::next_sector_end`]; each returns [`ScanReport`]s
//! (ids only), after which [`Tracker::tracks`] and [`Tracker::take_deleted`] give the
//! tracks (`argus run surveillance` scores confirmed tracks from them with
//! `argus_sim::Ospa`, `Gospa` and `TrackStatistics`).
//!
//! ```
//! use argus_core_math::{Matrix, Vector};
//! use argus_tracker::{
//!     Input, Output, Plot, SensorId, Session, TrackEvent, TrackStatus, TrackerConfig,
//! };
//!
//! let mut session = Session::new(TrackerConfig::new(vec![SensorId(0)]))?;
//! let r = Matrix::<2, 2>::identity() * 900.0;
//! let mut out = Vec::new();
//! for k in 0..4_u32 {
//!     let t = 5.0 * f64::from(k);
//!     let plot = Plot::cartesian(t, SensorId(0), Vector::<2>::new(200.0 * t, 0.0), r)?;
//!     session.push(Input::Plot { plot, tag: 100 + u64::from(k) }, &mut out)?;
//! }
//! session.push(Input::End, &mut out)?;
//! // Four scans (each concluded by the next plot, the last by the end), then the end.
//! let Some(Output::Scan(second)) = out.get(1) else { panic!() };
//! assert_eq!(second.report.initiated.len(), 1);
//! assert_eq!(second.rows[0].event, TrackEvent::Started);
//! let Some(Output::Scan(third)) = out.get(2) else { panic!() };
//! assert_eq!(third.rows[0].event, TrackEvent::Confirmed);
//! assert_eq!(third.rows[0].plot.map(|p| p.time()), Some(10.0));
//! let Some(Output::End(live)) = out.last() else { panic!() };
//! assert_eq!(live[0].status, TrackStatus::Confirmed);
//!
//! // A plot from an unknown sensor is named by its tag when its scan is handed in.
//! let plot = Plot::cartesian(20.0, SensorId(7), Vector::<2>::new(0.0, 0.0), r)?;
//! session.push(Input::Plot { plot, tag: 42 }, &mut out)?;
//! let e = session.push(Input::EndOfScan, &mut out).unwrap_err();
//! assert_eq!(e.tag, Some(42));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # The single-target mode
//! [`single`] is the engine of `argus track` without a `[tracker]` table: one estimator
//! over every plot of a run, no association. A [`SingleTarget`] is built from an
//! [`EstimatorSpec`] (KF or EKF on the 2-D or 3-D CV model, an IMM of 1 …
//! [`single::MAX_MODELS`] CV / fixed-rate CT Kalman filters, seed 000's multi-IMM, the
//! aircraft IMM), its sensors ([`single::SingleSensor`]) and an optional [`Smoothing`];
//! [`SingleTarget::run`] takes the plots, each with the caller's tag
//! ([`single::TaggedPlot`], e.g. a file line), and returns one [`single::Estimate`] per
//! row (the estimate with covariance, the IMMs' mode probabilities, the multi-IMM's noise
//! estimate, the aircraft IMM's turn rate, with smoothing the smoothed values) and which
//! values the rows have ([`single::Columns`]), or a [`SingleError`] naming the plot's tag.
//! [`smooth`] holds the smoothing it shares with the command's smoothing of the tracker's
//! tracks: RTS over recorded rows ([`smooth::rts_rows`]), the IMMs' forward-pass records
//! ([`smooth::ModeRecorder`]), fixed interval or fixed lag ([`Smoothing`]), and a
//! [`smooth::Failure`] naming the step and time that could not be smoothed.
//!
//! # Not yet here
//! JPDA with the multi-IMM (refused by the configuration); the
//! multi-IMM and the aircraft IMM with Cartesian plots (refused per plot); the multi-IMM
//! with one noise estimate per sensor (all sensors feeding a track share its estimate);
//! 3-D (spherical) plots. (The two-mode IMM [`EstimatorConfig::ImmCv2`] has CV modes
//! only; coordinated turns are the aircraft IMM's, [`EstimatorConfig::Aircraft`].)
//!
//! # Example
//! ```
//! use argus_core_math::{Matrix, Vector};
//! use argus_tracker::{Plot, SensorId, TrackStatus, Tracker, TrackerConfig};
//!
//! let mut tracker = Tracker::new(TrackerConfig::new(vec![SensorId(0)]))?;
//! // One target at 200 m/s along x, seen every 5 s with σ = 30 m.
//! let r = Matrix::<2, 2>::identity() * 900.0;
//! for k in 0..6 {
//!     let t = 5.0 * f64::from(k);
//!     let plot = Plot::cartesian(t, SensorId(0), Vector::<2>::new(200.0 * t, 0.0), r)?;
//!     tracker.process(&[plot])?;
//! }
//! // Initiated at the 2nd plot, confirmed at the 3rd (3 of 4).
//! assert_eq!(tracker.tracks().len(), 1);
//! assert_eq!(tracker.tracks()[0].status(), TrackStatus::Confirmed);
//! assert_eq!(tracker.tracks()[0].confirmed_at(), Some(10.0));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod aircraft;
mod assign;
mod config;
mod error;
mod estimator;
mod field;
mod grid;
mod innovation;
mod jpda;
mod management;
mod pda;
mod plot;
mod rotation;
mod session;
pub mod single;
pub mod smooth;
mod state;
mod track;
mod tracker;
mod tuning;
mod two_mode;

/// The aircraft IMM's tuning and mixing rule (from `argus-imm`), re-exported for
/// [`EstimatorConfig::Aircraft`].
pub use argus_imm::{AircraftTuning, Augmentation};
/// The plot vocabulary the tracker takes (from `argus-sensors`), re-exported.
pub use argus_sensors::{Plot, SensorId};
pub use config::{
    AssociationConfig, EstimatorConfig, PolarNoise, ScoreConfig, SensorConfig, TrackerConfig,
};
pub use error::TrackerError;
pub use field::{AssociationField, ConfigField, EstimatorField, ScoreField, SensorField};
pub use rotation::{Rotation, RotationDirection};
pub use session::{Concluded, Input, Output, Session, SessionError, TrackEvent, TrackSnapshot};
pub use single::{EstimatorSpec, SingleError, SingleTarget};
pub use smooth::Smoothing;
pub use state::{EstimatorState, MULTI_IMM_HYPOTHESES, ModeProbabilities};
pub use track::{DeletionReason, Track, TrackId, TrackStatus};
pub use tracker::{ScanReport, Tracker};
pub use tuning::{TUNABLES, Tunable};
pub use two_mode::{TwoModeImm, two_mode_imm};
