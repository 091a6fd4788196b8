//! One step of the tabulated jump-Markov problem ([`super::GibbsProblem`]): what the
//! sweep's Kalman pieces ([`super::kalman`]) read.

use argus_core_math::{Matrix, Vector};

/// One step's models: the transitions of every mode into it and its plot.
#[derive(Debug, Clone)]
pub(super) struct StepModel<const N: usize, const D: usize, const R: usize> {
    pub(super) f: [Matrix<N, N>; R],
    pub(super) q: [Matrix<N, N>; R],
    pub(super) h: Matrix<D, N>,
    pub(super) r: Matrix<D, D>,
    pub(super) z: Vector<D>,
    pub(super) info: Matrix<N, N>,
    pub(super) info_z: Vector<N>,
}
