//! The error type of the scenarios.

use std::path::PathBuf;

/// What is wrong with one parameter setting (the key is in [`ScenarioError::Param`]).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ParamProblem {
    /// A setting without `=` (the key holds the whole setting).
    Syntax,
    /// The scenario has no parameter of this name.
    Unknown {
        /// The scenario's keys.
        known: Vec<&'static str>,
    },
    /// One item of the value is not a number.
    NotANumber {
        /// The value as given (a single number or a comma list).
        value: String,
        /// The item that does not parse.
        item: String,
    },
    /// One item of the value lies outside the allowed range (or is not finite).
    OutOfRange {
        /// The value as given.
        value: String,
        /// The offending item.
        item: String,
        /// Smallest allowed value.
        min: f64,
        /// Largest allowed value.
        max: f64,
        /// Unit and meaning of the parameter.
        help: &'static str,
    },
    /// A list of values where the scenario needs one.
    List {
        /// How many values were given.
        len: usize,
    },
    /// The value does not fit with another parameter, e.g. `speed_min` above `speed_max`.
    Conflict {
        /// The value of this key.
        value: f64,
        /// Why, naming the other parameter (`exceeds range=5000`).
        reason: String,
    },
    /// The value is refused by what it parameterises (e.g. a distribution).
    Rejected {
        /// Why.
        reason: String,
    },
    /// The scenario asked for a key it did not declare (a bug in the scenario).
    Undeclared,
}

impl std::fmt::Display for ParamProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Syntax => write!(f, "expected key=value"),
            Self::Unknown { known } => write!(f, "unknown (known: {})", known.join(", ")),
            Self::NotANumber { value, item } => write!(f, "{value}: {item:?} is not a number"),
            Self::OutOfRange {
                value,
                item,
                min,
                max,
                help,
            } => write!(f, "{value}: {item} must lie in [{min}, {max}] ({help})"),
            Self::List { len } => write!(f, "takes one value here, got a list of {len}"),
            Self::Conflict { value, reason } => write!(f, "{value} {reason}"),
            Self::Rejected { reason } => write!(f, "{reason}"),
            Self::Undeclared => write!(f, "not declared by the scenario"),
        }
    }
}

/// What went wrong in a scenario.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ScenarioError {
    /// A parameter setting is bad.
    #[error("parameter {key}: {problem}")]
    Param {
        /// The parameter's key.
        key: String,
        /// What is wrong.
        problem: ParamProblem,
    },
    /// No scenario of this name.
    #[error("unknown scenario '{name}' (known: {})", known.join(", "))]
    UnknownScenario {
        /// The name asked for.
        name: String,
        /// The registered names.
        known: Vec<&'static str>,
    },
    /// The scenario runs whole only (it has no per-run records).
    #[error("scenario '{scenario}' does not write per-run records yet: run it whole")]
    NotSplittable {
        /// The scenario.
        scenario: &'static str,
    },
    /// The scenario has no fixed scene to export.
    #[error("{scenario}: {reason}")]
    NoScene {
        /// The scenario.
        scenario: &'static str,
        /// Why.
        reason: &'static str,
    },
    /// The parameters leave the scenario nothing to compute (no plot, no run, no target …).
    #[error("{scenario}: {message}")]
    Degenerate {
        /// The scenario.
        scenario: &'static str,
        /// What is missing.
        message: String,
    },
    /// The experiment's library configuration rejected the parameters.
    #[error("{scenario}: {source}")]
    Config {
        /// The scenario.
        scenario: &'static str,
        /// The experiment's error.
        source: argus_adaptive::AdaptiveError,
    },
    /// A random distribution rejected its parameters.
    #[error("{what}: {message}")]
    Distribution {
        /// Which distribution.
        what: &'static str,
        /// The distribution's error.
        message: String,
    },
    /// A per-run record does not parse as a record of this scenario.
    #[error("{}:{line}: field 'record': not a record of this scenario: {message}", file.display())]
    Record {
        /// Where the record came from (`<run N>` when computed in this process).
        file: PathBuf,
        /// 1-based line in that file.
        line: u64,
        /// The parser's error.
        message: String,
    },
    /// A run's record cannot be serialised.
    #[error("run {run}: cannot serialise: {message}")]
    Serialize {
        /// The run index.
        run: u64,
        /// The serialiser's error.
        message: String,
    },
    /// The simulation rejected a parameter.
    #[error("simulation: {0}")]
    Sim(#[from] argus_sim::SimError),
    /// A filter step failed.
    #[error("filter: {0}")]
    Filter(#[from] argus_filters::FilterError),
    /// A measurement model rejected a value.
    #[error("sensor: {0}")]
    Sensor(#[from] argus_sensors::SensorError),
    /// A motion model rejected a value.
    #[error("motion model: {0}")]
    Motion(#[from] argus_motion_models::MotionError),
    /// A numerical check failed.
    #[error("math: {0}")]
    Math(#[from] argus_core_math::MathError),
    /// An IMM or multi-IMM rejected a value.
    #[error("imm: {0}")]
    Imm(#[from] argus_imm::ImmError),
    /// The IMM smoother refused a recorded track.
    #[error("imm smoothing: {0}")]
    ImmSmooth(#[from] argus_imm::ImmSmoothError),
    /// The Gibbs smoother refused a problem or failed at a step.
    #[error("gibbs smoothing: {0}")]
    Gibbs(#[from] argus_imm::smooth::gibbs::GibbsError),
    /// Gating or data association rejected a value.
    #[error("association: {0}")]
    Association(#[from] argus_association::AssociationError),
    /// Bias estimation rejected a value.
    #[error("registration: {0}")]
    Registration(#[from] argus_registration::RegistrationError),
    /// The adaptive-R decoupled filter rejected a value.
    #[error("adaptive filter: {0}")]
    Adaptive(#[from] argus_adaptive::AdaptiveError),
    /// The ADS-B truth did not read or clean.
    #[error("ads-b: {0}")]
    Adsb(#[from] argus_adsb::AdsbError),
    /// A geodetic conversion failed.
    #[error("geography: {0}")]
    Geo(#[from] argus_geo::GeoError),
    /// Scoring the tracks against the truth failed.
    #[error("scoring: {0}")]
    Score(#[from] argus_score::ScoreError),
    /// The multi-target tracker rejected a configuration or a plot.
    #[error("tracker: {0}")]
    Tracker(#[from] argus_tracker::TrackerError),
}

impl ScenarioError {
    /// A parameter error on `key`.
    pub fn param(key: impl Into<String>, problem: ParamProblem) -> Self {
        Self::Param {
            key: key.into(),
            problem,
        }
    }
}
