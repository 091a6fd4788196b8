"""Argus radar target tracking from Python, on the Rust core.

Filters, stateful like FilterPy's (the object owns ``x`` and ``P``) or functional (the
estimate goes in, a new one comes out)::

    import numpy as np
    import argus_tracking as at

    kf = at.KalmanFilter("cv", q=0.5, R=np.diag([100.0, 100.0]), x=x0, P=P0)
    kf.predict(1.0)                             # kf.x, kf.P change in place
    kf.update(z)
    x, P = kf.predict(x, P, dt=1.0)             # functional: kf's own state untouched
    x, P = kf.update(x, P, z)
    run = kf.run(times, plots, x0, P0)          # the whole array in one call

- :class:`KalmanFilter`, :class:`ExtendedKalmanFilter`, :class:`UnscentedKalmanFilter`
  on the ``"cv"`` / ``"ca"`` / ``"ct"`` planar models with Cartesian or polar sensors and
  the ``"cv3"`` / ``"ca3"`` spatial models with Cartesian or spherical (range, azimuth,
  elevation) sensors;
- :class:`Imm`, :class:`MultiImm` (seed 000's noise estimator), :class:`DifferenceImm`;
- :class:`Tracker` (a stream of scans) and :func:`track` (a file's worth), configured
  exactly like ``argus track``;
- :func:`list_scenarios`, :func:`run_scenario`: the papers' Monte Carlo campaigns;
- :func:`nees`, :func:`nis`, :func:`chi2_interval`, :func:`ospa`, :func:`gospa`, and
  :func:`score_tracks` (``argus score``: the real-traffic track scoring).

State order: ``[x, vx, y, vy]`` (CV, CT), ``[x, vx, ax, y, vy, ay]`` (CA),
``[x, vx, y, vy, z, vz]`` (CV3) or ``[x, vx, ax, y, vy, ay, z, vz, az]`` (CA3); metres,
seconds, radians. Every error is an :class:`ArgusError`; bad input is an
:class:`InvalidInputError` (also a ``ValueError``) naming the argument, index and problem.
Long calls release the GIL.
"""

from __future__ import annotations

from . import _native
from ._native import (
    DifferenceImm,
    ExtendedKalmanFilter,
    Imm,
    KalmanFilter,
    MultiImm,
    UnscentedKalmanFilter,
)
from ._results import FilterRun, ImmRun
from .errors import (
    ArgusError,
    ArgusOSError,
    InvalidInputError,
    NumericalError,
    UnknownScenarioError,
)
from .metrics import chi2_interval, gospa, nees, nis, ospa
from .scenarios import list_scenarios, run_scenario
from .score import score_tracks
from .tracking import Tracker, track

__all__ = [
    "ArgusError",
    "ArgusOSError",
    "DifferenceImm",
    "ExtendedKalmanFilter",
    "FilterRun",
    "Imm",
    "ImmRun",
    "InvalidInputError",
    "KalmanFilter",
    "MultiImm",
    "NumericalError",
    "Tracker",
    "UnknownScenarioError",
    "UnscentedKalmanFilter",
    "chi2_interval",
    "gospa",
    "list_scenarios",
    "nees",
    "nis",
    "ospa",
    "run_scenario",
    "score_tracks",
    "track",
]

__version__ = "0.1.0"
del _native
