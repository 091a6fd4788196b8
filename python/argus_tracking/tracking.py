"""Multi-target tracking configured like ``argus track``: :func:`track` runs the command's
own pipeline (same configuration schema, same numbers, same tracks CSV columns) and
:class:`Tracker` feeds its multi-target tracker scan by scan.

Plots are a numpy structured array, a pandas DataFrame or a dict of 1-D arrays with the
plot file's columns (``t, sensor`` and ``range, azimuth[, elevation]`` or
``x, y[, z], r_xx, r_xy, r_yy[, ...]``; optional ``amplitude`` and ``origin``; see
docs/FORMATS.md). Configurations are TOML text, a path to a TOML file, or a dict of the
same schema. Errors name the plot table as ``plots`` with the line of the equivalent
plot file (line 1 is the header, so row ``i`` is line ``i + 2``) and the field.
"""

from __future__ import annotations

import json
import os
from typing import Any, Optional, Union

import numpy as np

from . import _native
from .errors import InvalidInputError

#: Tracks CSV columns that hold text or integers; every other column is float64.
_TEXT = {"status": "U20", "reason": "U20"}
_INT = {"sensor", "track"}

Config = Union[str, "os.PathLike[str]", "dict[str, Any]"]


def _columns(plots: Any, name: str = "plots") -> "tuple[list[str], list[Any]]":
    """The column names and value sequences of a table (argument ``name``)."""
    if hasattr(plots, "dtype") and getattr(plots.dtype, "names", None):
        names = list(plots.dtype.names)
        return names, [plots[n] for n in names]
    if hasattr(plots, "columns") and hasattr(plots, "__getitem__"):  # pandas DataFrame
        names = [str(c) for c in plots.columns]
        return names, [plots[c].to_numpy() for c in plots.columns]
    if isinstance(plots, dict):
        names = [str(k) for k in plots]
        return names, [np.asarray(v) for v in plots.values()]
    raise InvalidInputError(
        f"argument '{name}': expected a numpy structured array, a pandas DataFrame or a dict "
        f"of columns, got {type(plots).__name__}",
        "argus_python::InputError",
    )


def _native_columns(plots: Any, name: str = "plots") -> "tuple[list[str], list[Any]]":
    """The column names and values of a table as the native module takes them: float64 or
    int64 arrays (booleans as integers), other columns as lists of str."""
    names, cols = _columns(plots, name)
    lengths = {len(c) for c in cols}
    if len(lengths) > 1:
        raise InvalidInputError(
            f"argument '{name}': columns of different lengths {sorted(lengths)}",
            "argus_python::InputError",
        )
    out = []
    for c in cols:
        a = np.asarray(c)
        if a.dtype.kind == "f":
            out.append(np.ascontiguousarray(a, dtype=np.float64))
        elif a.dtype.kind in "iub":
            out.append(np.ascontiguousarray(a, dtype=np.int64))
        else:
            out.append([str(v) for v in a.tolist()])
    return names, out


def _table(columns: "dict[str, Any]", as_pandas: bool) -> Any:
    """The tracks table of the native module's columns (a numpy structured array, or a
    pandas DataFrame)."""
    header = list(columns)
    n = len(next(iter(columns.values()))) if columns else 0
    dtype = [(h, _TEXT.get(h, "i8" if h in _INT else "f8")) for h in header]
    table = np.empty(n, dtype=dtype)
    for h in header:
        table[h] = columns[h]
    if as_pandas:
        import pandas as pd

        return pd.DataFrame({h: table[h] for h in header})
    return table


def tracks_table(text: str, as_pandas: bool = False) -> Any:
    """A tracks CSV text (a file of ``argus track``) as a numpy structured array (or a
    pandas DataFrame), read by the native module."""
    return _table(_native.tracks_text_columns(text), as_pandas)


def _is_pandas(obj: Any) -> bool:
    return type(obj).__module__.startswith("pandas")


def _config(config: Config) -> "tuple[str, str]":
    """The configuration as the native module takes it: ``("path", p)`` for a file (read
    in Rust), ``("text", toml)`` or ``("json", text)`` for a dict (turned into TOML in
    Rust)."""
    if isinstance(config, dict):
        return ("json", json.dumps(config))
    if isinstance(config, os.PathLike):
        return ("path", os.fspath(config))
    if isinstance(config, str):
        if "\n" not in config and "=" not in config and os.path.exists(config):
            return ("path", config)
        return ("text", config)
    raise InvalidInputError(
        "argument 'config': expected TOML text, a path or a dict, got "
        f"{type(config).__name__}",
        "argus_python::InputError",
    )


def track(
    plots: Any,
    config: Config,
    *,
    as_pandas: Optional[bool] = None,
    summary: bool = False,
    smooth: Union[None, bool, int, float] = None,
) -> Any:
    """Runs ``argus track`` on ``plots`` with ``config``; returns the tracks table with the
    tracks CSV's columns and values (a structured array, or a DataFrame when
    ``as_pandas`` or when ``plots`` is one). With ``summary=True`` returns
    ``(table, summary)``, the summary being the command's ``<out>.summary.json`` (multi-
    target jobs; ``None`` otherwise) without its file names. ``smooth`` adds the smoothed
    columns as the command's flags do: ``True`` is ``--smooth`` (fixed interval), an int
    ``N`` is ``--smooth-lag N``, a float ``S`` is ``--smooth-lag-seconds S``. The GIL is
    released."""
    flags: "dict[str, Any]" = {}
    if smooth is True:
        flags["smooth"] = True
    elif isinstance(smooth, (int, np.integer)) and not isinstance(smooth, bool):
        flags["smooth_lag"] = int(smooth)
    elif isinstance(smooth, (float, np.floating)):
        flags["smooth_lag_seconds"] = float(smooth)
    if as_pandas is None:
        as_pandas = _is_pandas(plots)
    names, cols = _native_columns(plots)
    kind, value = _config(config)
    columns, doc = _native.track_columns(names, cols, kind, value, **flags)
    table = _table(columns, as_pandas)
    return (table, doc) if summary else table


class Tracker:
    """The multi-target tracker of an ``argus track`` configuration with a ``[tracker]``
    table, fed a stream of plots.

    Each :meth:`process` call takes whole scans (plots grouped by ``(t, sensor)`` in
    order, as ``argus track`` groups a file) and returns one row per track per scan,
    with the tracks CSV's columns; the rows over a stream equal ``track()``'s over the
    concatenated plots. On an error the tracker is left as it was.
    """

    def __init__(self, config: Config) -> None:
        self._stream = _native.TrackerStream(*_config(config))

    def process(self, plots: Any, *, as_pandas: Optional[bool] = None) -> Any:
        """Processes the scans in ``plots``; returns their rows (structured array or
        DataFrame). The GIL is released."""
        if as_pandas is None:
            as_pandas = _is_pandas(plots)
        return _table(self._stream.process(*_native_columns(plots)), as_pandas)
