"""The papers' experiments: the scenario list and Monte Carlo campaigns."""

from __future__ import annotations

import json
from typing import Any, Optional, Union

import numpy as np

from . import _native


def list_scenarios() -> "list[dict[str, Any]]":
    """Every scenario: ``name``, ``description``, ``default_runs`` and ``params`` (each with
    ``key``, ``default``, ``min``, ``max``, ``help``)."""
    return json.loads(_native.list_scenarios_json())


def _setting(key: str, value: Any) -> str:
    if isinstance(value, bool):
        value = float(value)
    if isinstance(value, (int, float, np.integer, np.floating)):
        return f"{key}={float(value)!r}"
    raise TypeError(f"parameter {key!r}: a number is expected, got {type(value).__name__}")


def run_scenario(
    name: str,
    runs: Optional[Union[int, "tuple[int, int]", range]] = None,
    seed: int = 1,
    **params: float,
) -> "dict[str, Any]":
    """Runs scenario ``name`` like ``argus run NAME --runs R --seed S --set k=v``.

    ``runs`` is a count ``N`` (runs ``0..N``), a pair or range ``(A, B)``, or ``None`` for
    the scenario's default count. Returns the content of the command's ``summary.json``
    (``scenario``, ``seed``, ``runs``, ``params``, ``results``, ``notes``; no file list)
    plus ``series``: for each series name, ``{"columns": [...], "rows": ndarray}``.
    The GIL is released while the campaign runs.
    """
    if runs is None:
        start, end = 0, None
    elif isinstance(runs, range):
        start, end = runs.start, runs.stop
    elif isinstance(runs, tuple):
        start, end = runs
    else:
        start, end = 0, int(runs)
    settings = [_setting(k, v) for k, v in params.items()]
    doc = json.loads(_native.run_scenario_json(name, int(start), end, int(seed), settings))
    for s in doc["series"].values():
        rows = s["rows"]
        s["rows"] = np.array(
            [[np.nan if v is None else v for v in r] for r in rows], dtype=np.float64
        ).reshape(len(rows), len(s["columns"]))
    return doc
