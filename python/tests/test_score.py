"""score_tracks() against `argus score` on the same files (the same report, to the bit),
from paths and from tables, and its errors."""

from __future__ import annotations

import json

import numpy as np
import pytest

import argus_tracking as at
from argus_tracking.tracking import tracks_table


@pytest.fixture(scope="module")
def scored(tmp_path_factory, run_cli, root):
    """The surveillance scenario's plots tracked by `argus track`, and `argus score`'s
    report of those tracks against the scenario's truth (grid 10 s, cut-off 500 m)."""
    d = tmp_path_factory.mktemp("score")
    run_cli("simulate", "surveillance", "--seed", "3", "--out", str(d / "surv.csv"))
    config = d / "surv.toml"
    config.write_text((root / "docs/examples/tracker.toml").read_text().replace("id = 1", "id = 0"))
    tracks = d / "tracks.csv"
    run_cli("track", "--config", str(config), "--plots", str(d / "surv.csv"), "--out", str(tracks))
    out = d / "score.json"
    run_cli("score", "--tracks", str(tracks), "--truth", str(d / "surv.truth.csv"), "--out",
            str(out), "--step", "10", "--cutoff", "500")
    return tracks, d / "surv.truth.csv", json.loads(out.read_text())


def test_score_tracks_equals_argus_score(scored):
    tracks, truth, cli = scored
    ours = at.score_tracks(tracks, truth, step=10.0, assign_cutoff=500.0)
    assert ours == cli
    # Something was scored: confirmed tracks were assigned to most of the truth.
    assert cli["summary"]["completeness"] > 0.5


def test_score_tracks_from_tables(scored):
    tracks, truth, cli = scored
    table = tracks_table(tracks.read_text())
    truth_table = tracks_table(truth.read_text())
    ours = at.score_tracks(table, truth_table, step=10.0, assign_cutoff=500.0)
    assert ours["summary"] == cli["summary"] and ours["series"] == cli["series"]
    pd = pytest.importorskip("pandas")
    frame = pd.read_csv(tracks)
    ours = at.score_tracks(frame, str(truth), step=10.0, assign_cutoff=500.0)
    assert ours["summary"] == cli["summary"]


def test_score_tracks_errors(scored, tmp_path):
    tracks, truth, _ = scored
    with pytest.raises(at.InvalidInputError, match="step"):
        at.score_tracks(tracks, truth, step=-1.0)
    with pytest.raises(at.ArgusOSError):
        at.score_tracks(tmp_path / "missing.csv", truth)
    bad = tmp_path / "bad.csv"
    bad.write_text("t,track,status,x,vx,y,vy\n0,1,confirmed,abc,0,0,0\n")
    with pytest.raises(at.InvalidInputError, match="bad.csv:2"):
        at.score_tracks(bad, truth)
    with pytest.raises(at.InvalidInputError, match="argument 'tracks'"):
        at.score_tracks(np.zeros(3), truth)
