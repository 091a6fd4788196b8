//! What the single-target KF / EKF loop ([`super::kf`]) does differently on 2-D and
//! 3-D plot files: the plot conversion, the two-point start, and the measurement model
//! of a converted plot; and the predict + update with a converted plot built on them.

use argus_core_math::{Gaussian, Matrix};
use argus_filters::{GaussianFilter, two_point_cv2, two_point_cv3};
use argus_sensors::CartesianPosition;

use super::error::SingleError;
use super::estimator::{position, position3, step};
use super::output::TaggedPlot;
use super::start::{Converted, Ctx, TwoPoint};

/// One dimension's parts: `D` the position's dimension, `N` the CV state's.
pub(super) struct Dim<const D: usize, const N: usize> {
    /// A plot's converted position and covariance ([`Ctx::convert2`], [`Ctx::convert3`]).
    pub(super) convert: for<'c> fn(&Ctx<'c>, &TaggedPlot) -> Result<Converted<D>, SingleError>,
    /// The two-point start of the CV state.
    pub(super) init: TwoPoint<D, N>,
    /// The measurement model of a converted plot of covariance `r`.
    model: fn(Matrix<D, D>) -> Result<CartesianPosition<N, D>, SingleError>,
}

/// 2-D plot files: the CV state `[x, vx, y, vy]`.
pub(super) const DIM2: Dim<2, 4> = Dim {
    convert: |ctx, p| ctx.convert2(p),
    init: two_point_cv2,
    model: |r| Ok(position(r)?),
};

/// 3-D plot files: the CV state `[x, vx, y, vy, z, vz]`.
pub(super) const DIM3: Dim<3, 6> = Dim {
    convert: |ctx, p| ctx.convert3(p),
    init: two_point_cv3,
    model: |r| Ok(position3(r)?),
};

impl<const D: usize, const N: usize> Dim<D, N> {
    /// `filter`'s predict over `dt` from `x` and update with plot `p` converted.
    ///
    /// # Errors
    /// The conversion's and the measurement model's errors; the filter's, at the plot's
    /// tag.
    pub(super) fn converted_step<F: GaussianFilter<N>>(
        &self,
        ctx: &Ctx<'_>,
        filter: &F,
        x: &Gaussian<N>,
        dt: f64,
        p: &TaggedPlot,
    ) -> Result<Gaussian<N>, SingleError> {
        let (z, r) = (self.convert)(ctx, p)?;
        Ok(step(filter, x, dt, &(self.model)(r)?, &z)
            .map_err(ctx.filter_error(p))?
            .0)
    }
}
