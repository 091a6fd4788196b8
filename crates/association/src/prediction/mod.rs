//! Off-line performance prediction in clutter: the HYCA recursion of the NN filter
//! and the information-reduction-factor recursion of the PDA filter.

mod hyca;
mod irf;
mod nn_moments;
mod predictor;

pub use hyca::hyca_factors;
pub use irf::pda_irf;
pub use nn_moments::{NnMoments, nn_moments};
pub use predictor::{
    LinearSystem, PerformancePredictor, PredictedFilter, PredictionStep, SteadyState,
};

#[cfg(test)]
mod tests;
