"""Type stubs of the native module (the Rust side of argus_tracking)."""

from os import PathLike
from typing import Any, Dict, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from ._results import FilterRun, ImmRun

ArrayLike = npt.ArrayLike
_Path = Union[str, PathLike]

class Filter:
    """Base of the filter classes. Stateful like FilterPy (the object owns ``x`` and ``P``:
    ``predict(dt)``, ``update(z)``) and functional (``predict(x, P, dt)``,
    ``update(x, P, z)``, ``step``, ``run``, ``smooth``: the own state is not touched)."""

    @property
    def dim_x(self) -> int: ...
    @property
    def dim_z(self) -> int: ...
    @property
    def model(self) -> str: ...
    @property
    def x(self) -> np.ndarray:
        """The own state mean (a new array); settable (checked)."""
    @x.setter
    def x(self, value: ArrayLike) -> None: ...
    @property
    def P(self) -> np.ndarray:
        """The own state covariance (a new array); settable (checked positive definite)."""
    @P.setter
    def P(self, value: ArrayLike) -> None: ...
    @property
    def nis(self) -> Optional[float]:
        """The NIS of the last stateful ``update(z)`` (``None`` before it / after a set)."""
    def set_state(self, x: ArrayLike, P: ArrayLike) -> None:
        """Sets the own ``(x, P)`` at once (checked together; unchanged on an error)."""
    @overload
    def predict(self, dt: float) -> None:
        """Predicts the own ``(x, P)`` over ``dt`` seconds in place."""
    @overload
    def predict(self, x: ArrayLike, P: ArrayLike, dt: float) -> Tuple[np.ndarray, np.ndarray]:
        """``(x, P)`` predicted over ``dt`` seconds."""
    @overload
    def update(self, z: ArrayLike) -> None:
        """Updates the own ``(x, P)`` with the plot ``z`` in place (NIS in ``nis``)."""
    @overload
    def update(self, x: ArrayLike, P: ArrayLike, z: ArrayLike) -> Tuple[np.ndarray, np.ndarray]:
        """``(x, P)`` updated with the plot ``z``."""
    def step(
        self, x: ArrayLike, P: ArrayLike, dt: float, z: ArrayLike
    ) -> Tuple[np.ndarray, np.ndarray]:
        """``predict`` over ``dt`` (none when 0) then ``update`` with ``z``."""
    def run(
        self,
        times: ArrayLike,
        plots: ArrayLike,
        x0: ArrayLike,
        P0: ArrayLike,
        t0: Optional[float] = None,
        *,
        reuse_gain: bool = True,
    ) -> FilterRun:
        """Filters ``plots`` (``n × dim_z``) at ``times`` from ``(x0, P0)`` at ``t0``. With
        ``reuse_gain`` the KF reuses the covariance recursion of an earlier step with the
        same ``dt`` and bit-identical prior covariance (the same result to the bit)."""
    def smooth(
        self,
        times: ArrayLike,
        plots: ArrayLike,
        x0: ArrayLike,
        P0: ArrayLike,
        t0: float,
    ) -> FilterRun:
        """Fixed-interval RTS (unscented RTS for the UKF) smoothing of the same run."""

class KalmanFilter(Filter):
    """Linear KF on ``"cv"`` (q = σ_a, m/s²), ``"ca"`` (q = σ_j, m/s³), ``"ct"`` (q = σ_v,
    turn rate ``omega`` rad/s) with a Cartesian position sensor of covariance ``R``
    (2 × 2), or on ``"cv3"`` / ``"ca3"`` with ``R`` 3 × 3. ``x`` / ``P``: the own starting
    estimate (default 0 and I, as FilterPy)."""

    def __init__(
        self,
        model: str = "cv",
        q: float = 1.0,
        R: Optional[ArrayLike] = None,
        *,
        omega: float = 0.0,
        joseph: bool = True,
        x: Optional[ArrayLike] = None,
        P: Optional[ArrayLike] = None,
    ) -> None: ...

class ExtendedKalmanFilter(Filter):
    """EKF with a polar radar (planar models; ``sigma_range`` m, ``sigma_azimuth`` rad, at
    ``sensor_position`` (x, y)), a spherical radar (``sensor="spherical"``, ``"cv3"`` /
    ``"ca3"``; also ``sigma_elevation`` rad, ``sensor_position`` (x, y, z)) or a Cartesian
    sensor (``sensor="cartesian"``, ``R``)."""

    def __init__(
        self,
        model: str = "cv",
        q: float = 1.0,
        *,
        sensor: str = "polar",
        sigma_range: Optional[float] = None,
        sigma_azimuth: Optional[float] = None,
        sigma_elevation: Optional[float] = None,
        sensor_position: Optional[Sequence[float]] = None,
        R: Optional[ArrayLike] = None,
        omega: float = 0.0,
        joseph: bool = True,
        x: Optional[ArrayLike] = None,
        P: Optional[ArrayLike] = None,
    ) -> None: ...

class UnscentedKalmanFilter(Filter):
    """UKF (scaled unscented transform ``alpha``, ``beta``, ``kappa``), sensors as the EKF."""

    def __init__(
        self,
        model: str = "cv",
        q: float = 1.0,
        *,
        sensor: str = "polar",
        sigma_range: Optional[float] = None,
        sigma_azimuth: Optional[float] = None,
        sigma_elevation: Optional[float] = None,
        sensor_position: Optional[Sequence[float]] = None,
        R: Optional[ArrayLike] = None,
        omega: float = 0.0,
        alpha: float = 1.0,
        beta: float = 2.0,
        kappa: float = 0.0,
        x: Optional[ArrayLike] = None,
        P: Optional[ArrayLike] = None,
    ) -> None: ...

_Model = Union[Tuple[str, float], Tuple[str, float, float]]

class ImmBase:
    """Base of the IMM classes: batch ``run``."""

    @property
    def modes(self) -> int: ...
    def run(
        self,
        times: ArrayLike,
        plots: ArrayLike,
        x0: ArrayLike,
        P0: ArrayLike,
        mu0: Optional[ArrayLike] = None,
        t0: Optional[float] = None,
    ) -> ImmRun: ...

class Imm(ImmBase):
    """IMM of KFs on ``("cv", q)`` / ``("ct", q, omega)`` models with Markov matrix
    ``transition``; Cartesian plots (``R``) or polar plots (σ, unbiased conversion)."""

    def __init__(
        self,
        models: Sequence[_Model],
        transition: ArrayLike,
        *,
        R: Optional[ArrayLike] = None,
        sigma_range: Optional[float] = None,
        sigma_azimuth: Optional[float] = None,
        sensor_position: Tuple[float, float] = (0.0, 0.0),
    ) -> None: ...

class MultiImm(ImmBase):
    """Seed 000's multi-IMM noise estimator over one polar radar's plots."""

    def __init__(
        self,
        models: Sequence[_Model],
        transition: ArrayLike,
        *,
        sigma_range: float,
        sigma_azimuth: float,
        sensor_position: Tuple[float, float] = (0.0, 0.0),
        n: int = 5,
        p: float = 0.1,
        clip: Optional[float] = None,
    ) -> None: ...

class DifferenceImm(ImmBase):
    """One IMM under range/azimuth variances from third differences of the raw plots."""

    def __init__(
        self,
        models: Sequence[_Model],
        transition: ArrayLike,
        *,
        sigma_range: float,
        sigma_azimuth: float,
        sensor_position: Tuple[float, float] = (0.0, 0.0),
        forgetting: float = 1.0,
        prior_count: float = 2.0,
    ) -> None: ...

class TrackerStream:
    def __init__(self, kind: str, value: str) -> None: ...
    def process(self, names: Sequence[str], columns: Sequence[Any]) -> Dict[str, Any]: ...

def track_columns(
    names: Sequence[str],
    columns: Sequence[Any],
    config_kind: str,
    config_value: str,
    smooth: bool = False,
    smooth_lag: Optional[int] = None,
    smooth_lag_seconds: Optional[float] = None,
) -> Tuple[Dict[str, Any], Optional[Dict[str, Any]]]: ...
def tracks_text_columns(text: str) -> Dict[str, Any]: ...
def toml_from_json(json: str) -> str: ...
def list_scenarios_json() -> str: ...
def run_scenario_json(
    name: str, start: int, end: Optional[int], seed: int, settings: Sequence[str]
) -> str: ...
def nees(x: ArrayLike, P: ArrayLike, truth: ArrayLike) -> np.ndarray: ...
def chi2_interval(dim: int, runs: int = 1, confidence: float = 0.95) -> Tuple[float, float]: ...
def ospa(truth: ArrayLike, estimates: ArrayLike, cutoff: float, order: float = 1.0) -> dict: ...
def gospa(truth: ArrayLike, estimates: ArrayLike, cutoff: float, order: float = 2.0) -> dict: ...
def score_json(tracks: tuple, truth: tuple, config: dict) -> str: ...
