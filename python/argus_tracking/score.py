"""Track scoring against truth (``argus score``): completeness, breaks per aircraft-hour,
identity swaps, spurious track fraction, position / velocity RMSE, time to confirm,
GOSPA and the rest of ``docs/scoring.md``."""

from __future__ import annotations

import json
import os
from typing import Any, Optional, Union

from . import _native
from .tracking import _native_columns

Table = Union[str, "os.PathLike[str]", Any]


def _table(table: Table, name: str) -> tuple:
    """A path as ``("path", p)``, a table (structured array, DataFrame, dict of columns)
    as ``("columns", names, columns, name)``."""
    if isinstance(table, (str, os.PathLike)):
        return ("path", os.fspath(table))
    names, columns = _native_columns(table, name)
    return ("columns", names, columns, name)


def score_tracks(
    tracks: Table,
    truth: Table,
    *,
    step: float = 5.0,
    start: Optional[float] = None,
    end: Optional[float] = None,
    assign_cutoff: float = 1000.0,
    max_track_age: float = 15.0,
    max_truth_gap: float = 10.0,
    gospa_cutoff: float = 1000.0,
    gospa_order: float = 2.0,
) -> "dict[str, Any]":
    """Scores ``tracks`` against ``truth``; returns the report ``argus score`` writes (a dict
    with ``config``, ``summary``, per-truth ``truths`` and the per-time ``series``).

    ``tracks``: the tracks CSV of ``argus track`` / :func:`track` (columns ``t, track,
    status, x, vx, y, vy``, others ignored), as a path or a table (numpy structured array,
    pandas DataFrame, dict of columns). ``truth``: ``t, target, x, vx, y, vy`` (what ``argus
    simulate`` writes beside its plots), likewise. Parameters (``docs/scoring.md``): grid
    ``step`` (s) from ``start`` to ``end`` (default: the truth's span), track-to-truth
    ``assign_cutoff`` (m), ``max_track_age`` (s) before a track counts as absent,
    ``max_truth_gap`` (s) not interpolated across, GOSPA ``gospa_cutoff`` (m) and
    ``gospa_order``. A malformed row raises :class:`InvalidInputError` naming the file (or
    argument), line and field; an unreadable file :class:`ArgusOSError`. The GIL is
    released while scoring.
    """
    config = {
        "step": step,
        "start": start,
        "end": end,
        "assign_cutoff": assign_cutoff,
        "max_track_age": max_track_age,
        "max_truth_gap": max_truth_gap,
        "gospa_cutoff": gospa_cutoff,
        "gospa_order": gospa_order,
    }
    text = _native.score_json(_table(tracks, "tracks"), _table(truth, "truth"), config)
    return json.loads(text)
