"""Python results equal the command's for the same input and seed: run_scenario against
`argus run`'s summary.json, track() against `argus track`'s tracks CSV and summary, the
Tracker stream against track()."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

import argus_tracking as at
from argus_tracking.tracking import tracks_table


def test_list_scenarios_matches_the_command(run_cli):
    names = [line.split()[0] for line in run_cli("scenarios").splitlines() if line.strip()]
    listed = at.list_scenarios()
    assert [s["name"] for s in listed] == names
    cv = next(s for s in listed if s["name"] == "cv-polar")
    assert cv["default_runs"] > 0 and any(p["key"] == "duration" for p in cv["params"])


@pytest.mark.parametrize(
    "name, runs, seed, params, sets",
    [
        ("cv-polar", 6, 3, {"duration": 40.0}, ["duration=40"]),
        ("gimpo", (2, 5), 7, {}, []),
    ],
)
def test_run_scenario_equals_argus_run(tmp_path, run_cli, name, runs, seed, params, sets):
    rng = f"{runs[0]}..{runs[1]}" if isinstance(runs, tuple) else str(runs)
    args = ["run", name, "--runs", rng, "--seed", str(seed), "--out", str(tmp_path)]
    for s in sets:
        args += ["--set", s]
    run_cli(*args)
    cli = json.loads((tmp_path / "summary.json").read_text())
    ours = at.run_scenario(name, runs=runs, seed=seed, **params)
    for key in ("scenario", "seed", "runs", "params", "results", "notes"):
        assert ours[key] == cli[key], key  # exact: the same f64s through the same JSON
    # The series are the CSVs the command wrote.
    for sname, s in ours["series"].items():
        with open(tmp_path / f"{sname}.csv") as f:
            rows = list(csv.reader(f))
        assert rows[0] == s["columns"]
        values = np.array([[float(v) if v else np.nan for v in r] for r in rows[1:]])
        np.testing.assert_array_equal(values, s["rows"], err_msg=sname)


def _plot_array(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    names = list(rows[0].keys())
    dt = [(n, "i8" if n == "sensor" else ("U40" if n == "origin" else "f8")) for n in names]
    conv = {"i8": int, "f8": float, "U40": str}
    return np.array([tuple(conv[t](r[n]) for n, t in dt) for r in rows], dtype=dt)


def _assert_tables_equal(a, b):
    assert a.dtype.names == b.dtype.names
    assert len(a) == len(b)
    for name in a.dtype.names:
        np.testing.assert_array_equal(a[name], b[name], err_msg=name)


@pytest.fixture(scope="module")
def surveillance_plots(tmp_path_factory, run_cli):
    d = tmp_path_factory.mktemp("sim")
    run_cli("simulate", "surveillance", "--seed", "3", "--out", str(d / "surv.csv"))
    return d / "surv.csv"


@pytest.fixture(scope="module")
def surveillance_config(tmp_path_factory, root):
    """docs/examples/tracker.toml for the surveillance scenario's radar (id 0)."""
    path = tmp_path_factory.mktemp("cfg") / "surv.toml"
    path.write_text((root / "docs/examples/tracker.toml").read_text().replace("id = 1", "id = 0"))
    return path


def test_track_equals_argus_track_multi_target(
    tmp_path, run_cli, root, surveillance_plots, surveillance_config
):
    for config, plots_path in (
        (root / "docs/examples/tracker.toml", root / "docs/examples/two-targets.csv"),
        (surveillance_config, surveillance_plots),
    ):
        out = tmp_path / "tracks.csv"
        run_cli("track", "--config", str(config), "--plots", str(plots_path), "--out", str(out))
        cli = tracks_table(out.read_text())
        plots = _plot_array(plots_path)
        table, summary = at.track(plots, config, summary=True)
        _assert_tables_equal(table, cli)
        cli_summary = json.loads(out.with_suffix(".summary.json").read_text())
        for key in ("config", "plots_file", "tracks_file"):
            cli_summary.pop(key)
        assert summary == cli_summary
        # Config as text and as a dict give the same rows.
        _assert_tables_equal(at.track(plots, config.read_text()), cli)
        import tomllib

        _assert_tables_equal(at.track(plots, tomllib.loads(config.read_text())), cli)


def test_tracker_stream_equals_track(surveillance_plots, surveillance_config):
    config = surveillance_config
    plots = _plot_array(surveillance_plots)
    whole = at.track(plots, config)
    tracker = at.Tracker(config)
    # Whole scans per call, several scans per call.
    keys = np.stack([plots["t"], plots["sensor"]], axis=1)
    change = np.flatnonzero(np.any(keys[1:] != keys[:-1], axis=1)) + 1
    scans = np.split(plots, change)
    parts = [tracker.process(np.concatenate(scans[i : i + 3])) for i in range(0, len(scans), 3)]
    _assert_tables_equal(np.concatenate(parts), whole)


def test_track_single_target_and_pandas(tmp_path, run_cli, root):
    pd = pytest.importorskip("pandas")
    config = tmp_path / "single.toml"
    config.write_text(
        "[[sensor]]\nid = 1\nposition = [0.0, 0.0]\nsigma_range = 50.0\nsigma_azimuth_deg = 0.06\n\n"
        '[estimator]\nkind = "kf-converted"\nsigma_a = 2.0\n'
    )
    plots_path = tmp_path / "one.csv"
    run_cli("simulate", "cv-polar", "--seed", "5", "--out", str(plots_path))
    out = tmp_path / "tracks.csv"
    run_cli("track", "--config", str(config), "--plots", str(plots_path), "--out", str(out))
    cli = tracks_table(out.read_text())
    # With the command's --smooth (fixed-interval RTS), the same smoothed columns.
    run_cli("track", "--config", str(config), "--plots", str(plots_path), "--out", str(out), "--smooth")
    smoothed = tracks_table(out.read_text())
    _assert_tables_equal(at.track(_plot_array(plots_path), config, smooth=True), smoothed)
    assert "xs" in smoothed.dtype.names
    frame = pd.read_csv(plots_path, dtype={"sensor": "int64"})
    ours = at.track(frame, config)
    assert isinstance(ours, pd.DataFrame)
    assert list(ours.columns) == list(cli.dtype.names)
    for name in cli.dtype.names:
        np.testing.assert_array_equal(ours[name].to_numpy(), cli[name], err_msg=name)
