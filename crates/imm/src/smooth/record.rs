//! What a recorded forward pass is whatever the IMM: time-ordered steps (never empty), the
//! failure that ended the record, the check of a sequence and the order of the backward
//! recursion. [`super::ImmTrack`] and the aircraft IMM's `AircraftTrack` keep their own
//! steps (different estimates and transitions) in a [`Record`].

use argus_filters::SmoothError;

use super::ImmSmoothError;
use crate::ImmError;

/// A step of a recorded forward pass.
pub(crate) trait RecordedStep {
    /// The step's time (s).
    fn time(&self) -> f64;
    /// Whether the step holds the transition from the step before.
    fn has_transition(&self) -> bool;
}

/// Checks a sequence of steps: times finite and increasing, a transition into every
/// later step.
pub(crate) fn validate<S: RecordedStep>(steps: &[S]) -> Result<(), SmoothError> {
    let first = steps.first().ok_or(SmoothError::Empty)?;
    if !first.time().is_finite() {
        return Err(SmoothError::TimeNotIncreasing {
            step: 0,
            prev: f64::NEG_INFINITY,
            now: first.time(),
        });
    }
    for (k, pair) in steps.windows(2).enumerate() {
        let (prev, now) = (pair[0].time(), pair[1].time());
        if !(now > prev && now.is_finite()) {
            return Err(SmoothError::TimeNotIncreasing {
                step: k + 1,
                prev,
                now,
            });
        }
        if !pair[1].has_transition() {
            return Err(SmoothError::MissingTransition { step: k + 1 });
        }
    }
    Ok(())
}

/// The backward recursion over `steps` (checked by [`validate`] first): `last` at the
/// final step, then `back(step k, step k + 1, smoothed k + 1, k)` down to step 0; the
/// results in time order.
pub(crate) fn backward_pass<S: RecordedStep, O>(
    steps: &[S],
    last: impl FnOnce(&S, usize) -> Result<O, ImmSmoothError>,
    mut back: impl FnMut(&S, &S, &O, usize) -> Result<O, ImmSmoothError>,
) -> Result<Vec<O>, ImmSmoothError> {
    validate(steps)?;
    let n = steps.len();
    let mut out = Vec::with_capacity(n);
    out.push(last(&steps[n - 1], n - 1)?);
    for k in (0..n - 1).rev() {
        let s = back(&steps[k], &steps[k + 1], &out[out.len() - 1], k)?;
        out.push(s);
    }
    out.reverse();
    Ok(out)
}

/// A forward pass's steps and the failure that ended it: after a failure every call
/// returns it, naming the step.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Record<S> {
    steps: Vec<S>,
    failure: Option<ImmSmoothError>,
}

impl<S: RecordedStep> Record<S> {
    /// A record starting with `first` (step 0).
    ///
    /// # Errors
    /// [`SmoothError::TimeNotIncreasing`] for a non-finite time.
    pub(crate) fn new(first: S) -> Result<Self, ImmSmoothError> {
        if !first.time().is_finite() {
            return Err(SmoothError::TimeNotIncreasing {
                step: 0,
                prev: f64::NEG_INFINITY,
                now: first.time(),
            }
            .into());
        }
        Ok(Self {
            steps: vec![first],
            failure: None,
        })
    }

    /// Room for `additional` more steps.
    pub(crate) fn reserve(&mut self, additional: usize) {
        self.steps.reserve(additional);
    }

    /// The recorded steps.
    pub(crate) fn steps(&self) -> &[S] {
        &self.steps
    }

    /// The latest step.
    pub(crate) fn latest(&self) -> &S {
        // Never empty: `new` pushes the first step and nothing removes one.
        &self.steps[self.steps.len() - 1]
    }

    /// The failure recorded, if any.
    pub(crate) fn failure(&self) -> Option<&ImmSmoothError> {
        self.failure.as_ref()
    }

    /// Records `e` as the failure; returns it.
    pub(crate) fn fail(&mut self, e: ImmSmoothError) -> ImmSmoothError {
        self.failure = Some(e.clone());
        e
    }

    /// `result`, or its error recorded (and returned) as the forward pass failing at `step`.
    ///
    /// # Errors
    /// [`ImmSmoothError::ForwardFailed`] with `result`'s error.
    pub(crate) fn forward<T>(
        &mut self,
        step: usize,
        result: Result<T, ImmError>,
    ) -> Result<T, ImmSmoothError> {
        result.map_err(|source| self.fail(ImmSmoothError::ForwardFailed { step, source }))
    }

    /// Checks `time` against the latest step (and that nothing failed); returns
    /// `(step, dt)` of the step to come.
    ///
    /// # Errors
    /// The recorded failure; [`SmoothError::TimeNotIncreasing`] (recorded).
    pub(crate) fn next_interval(&mut self, time: f64) -> Result<(usize, f64), ImmSmoothError> {
        if let Some(e) = &self.failure {
            return Err(e.clone());
        }
        let step = self.steps.len();
        let prev = self.steps[step - 1].time();
        if !(time > prev && time.is_finite()) {
            return Err(self.fail(
                SmoothError::TimeNotIncreasing {
                    step,
                    prev,
                    now: time,
                }
                .into(),
            ));
        }
        Ok((step, time - prev))
    }

    /// Appends a step (its time checked by [`Record::next_interval`]).
    pub(crate) fn push(&mut self, step: S) {
        self.steps.push(step);
    }

    /// The steps to smooth, or the recorded failure.
    ///
    /// # Errors
    /// The recorded failure.
    pub(crate) fn to_smooth(&self) -> Result<&[S], ImmSmoothError> {
        match &self.failure {
            Some(e) => Err(e.clone()),
            None => Ok(&self.steps),
        }
    }

    /// Steps `first ..= last` to smooth, or the recorded failure.
    ///
    /// # Errors
    /// The recorded failure; [`SmoothError::LengthMismatch`] when the window is empty or
    /// reaches past the latest step.
    pub(crate) fn window(&self, first: usize, last: usize) -> Result<&[S], ImmSmoothError> {
        let steps = self.to_smooth()?;
        steps
            .get(first..=last)
            .filter(|w| !w.is_empty())
            .ok_or_else(|| {
                SmoothError::LengthMismatch {
                    what: "smoothing window's last step (against the recorded steps)",
                    expected: steps.len(),
                    found: last.saturating_add(1),
                }
                .into()
            })
    }
}
