"""Consistency and multi-target metrics."""

from __future__ import annotations

from typing import Any

import numpy as np

from . import _native


def nees(x: Any, P: Any, truth: Any) -> np.ndarray:
    """Normalised estimation error squared of every row: ``(x - truth)ᵀ P⁻¹ (x - truth)``.

    ``x`` and ``truth`` are ``n × d``, ``P`` is ``n × d × d`` (``d`` from 1 to 6).
    """
    return _native.nees(x, P, truth)


def nis(innovation: Any, S: Any) -> np.ndarray:
    """Normalised innovation squared of every row: ``νᵀ S⁻¹ ν``."""
    nu = np.asarray(innovation, dtype=np.float64)
    return _native.nees(nu, S, np.zeros_like(nu))


def chi2_interval(dim: int, runs: int = 1, confidence: float = 0.95) -> "tuple[float, float]":
    """Two-sided ``confidence`` interval of the average of ``runs`` NEES (or NIS) values of
    a ``dim``-dimensional statistic: ``χ²_{dim·runs}((1 ∓ confidence)/2) / runs``."""
    return _native.chi2_interval(dim, runs, confidence)


def ospa(truth: Any, estimates: Any, cutoff: float, order: float = 1.0) -> "dict[str, float]":
    """OSPA distance between point sets ``truth`` (``m × d``) and ``estimates`` (``n × d``),
    with its localisation and cardinality components."""
    return _native.ospa(truth, estimates, cutoff, order)


def gospa(truth: Any, estimates: Any, cutoff: float, order: float = 2.0) -> "dict[str, float]":
    """GOSPA (α = 2) between point sets, with its localisation, missed and false parts and
    the assigned / missed / false counts."""
    return _native.gospa(truth, estimates, cutoff, order)
