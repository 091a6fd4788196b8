"""Result containers returned by the native module."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class FilterRun(NamedTuple):
    """A batch filter run: one row per plot."""

    #: Posterior states, ``n × dim_x``.
    x: np.ndarray
    #: Posterior covariances, ``n × dim_x × dim_x``.
    P: np.ndarray
    #: Normalised innovation squared of each plot, ``n``.
    nis: np.ndarray


class ImmRun(NamedTuple):
    """A batch IMM run: one row per plot."""

    #: Combined posterior states, ``n × 4``.
    x: np.ndarray
    #: Combined posterior covariances, ``n × 4 × 4``.
    P: np.ndarray
    #: Motion-mode probabilities after each update, ``n × modes``.
    mode_probabilities: np.ndarray
    #: Measurement-noise estimate ``(sigma_range, sigma_azimuth)`` after each update,
    #: ``n × 2`` (the multi-IMM and the difference estimator; ``None`` for a plain IMM).
    noise: "np.ndarray | None"
