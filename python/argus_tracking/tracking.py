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

import csv
import io
import json
import os
import tempfile
from typing import Any, Optional, Union

import numpy as np

from . import _native
from .errors import ArgusError, InvalidInputError

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


def _cell(v: Any) -> str:
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    if isinstance(v, (bool, np.bool_)):
        return str(int(v))
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    return str(v)


def plots_text(plots: Any, name: str = "plots") -> str:
    """The CSV text of a table (a plot table, or the tracks / truth of ``score_tracks``),
    floats written so they read back exactly; ``name`` is the argument named in errors."""
    names, cols = _columns(plots, name)
    lengths = {len(c) for c in cols}
    if len(lengths) > 1:
        raise InvalidInputError(
            f"argument '{name}': columns of different lengths {sorted(lengths)}",
            "argus_python::InputError",
        )
    out = io.StringIO()
    out.write(",".join(names) + "\n")
    text_cols = [[_cell(v) for v in (c.tolist() if hasattr(c, "tolist") else c)] for c in cols]
    for row in zip(*text_cols):
        out.write(",".join(row) + "\n")
    return out.getvalue()


def tracks_table(text: str, as_pandas: bool = False) -> Any:
    """A tracks CSV text as a numpy structured array (or a pandas DataFrame)."""
    reader = csv.reader(io.StringIO(text))
    header = next(reader, [])
    rows = list(reader)
    n = len(rows)
    dtype = [(h, _TEXT.get(h, "i8" if h in _INT else "f8")) for h in header]
    table = np.empty(n, dtype=dtype)
    for j, (h, dt) in enumerate(dtype):
        col = [r[j] for r in rows]
        if dt == "f8":
            table[h] = [float(v) if v != "" else np.nan for v in col]
        elif dt == "i8":
            table[h] = [int(v) for v in col]
        else:
            table[h] = col
    if as_pandas:
        import pandas as pd

        return pd.DataFrame({h: table[h] for h in header})
    return table


def _is_pandas(obj: Any) -> bool:
    return type(obj).__module__.startswith("pandas")


def _config_file(config: Config, folder: str) -> str:
    """A path to the configuration: a file as given, or text / a dict written to
    ``folder``."""
    if isinstance(config, dict):
        text = _native.toml_from_json(json.dumps(config))
    elif isinstance(config, os.PathLike):
        return os.fspath(config)
    elif isinstance(config, str):
        if "\n" not in config and "=" not in config and os.path.exists(config):
            return config
        text = config
    else:
        raise InvalidInputError(
            "argument 'config': expected TOML text, a path or a dict, got "
            f"{type(config).__name__}",
            "argus_python::InputError",
        )
    path = os.path.join(folder, "config.toml")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    return path


def _clean(e: ArgusError, folder: str) -> ArgusError:
    """The same error with the temporary folder's path removed from its message."""
    msg = e.message.replace(folder + os.sep, "")
    return type(e)(msg, e.rust_error)


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
    text = plots_text(plots)
    with tempfile.TemporaryDirectory(prefix="argus-track-") as folder:
        try:
            cfg = _config_file(config, folder)
            plots_path = os.path.join(folder, "plots")
            with open(plots_path, "w", encoding="utf-8") as f:
                f.write(text)
            out = os.path.join(folder, "tracks.csv")
            _, summary_path = _native.track_files(cfg, plots_path, out, **flags)
        except ArgusError as e:
            raise _clean(e, folder) from None
        with open(out, encoding="utf-8") as f:
            table = tracks_table(f.read(), as_pandas)
        doc = None
        if summary and summary_path is not None:
            with open(summary_path, encoding="utf-8") as f:
                doc = json.load(f)
            for key in ("config", "plots_file", "tracks_file"):
                doc.pop(key, None)
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
        with tempfile.TemporaryDirectory(prefix="argus-tracker-") as folder:
            try:
                self._stream = _native.TrackerStream(_config_file(config, folder))
            except ArgusError as e:
                raise _clean(e, folder) from None

    def process(self, plots: Any, *, as_pandas: Optional[bool] = None) -> Any:
        """Processes the scans in ``plots``; returns their rows (structured array or
        DataFrame). The GIL is released."""
        if as_pandas is None:
            as_pandas = _is_pandas(plots)
        text = self._stream.process(plots_text(plots), "plots")
        return tracks_table(text, as_pandas)
