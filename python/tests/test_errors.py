"""Every bad input raises the package's exception, naming the argument, the index and the
problem, and leaves the object as it was."""

from __future__ import annotations

import numpy as np
import pytest

import argus_tracking as at
from argus_tracking import InvalidInputError, UnknownScenarioError

R = np.diag([100.0, 100.0])
X = np.array([1000.0, 10.0, 2000.0, -5.0])
P = np.diag([100.0, 10.0, 100.0, 10.0])


@pytest.fixture
def kf():
    return at.KalmanFilter("cv", q=1.0, R=R)


def test_exceptions_are_value_errors_with_the_rust_type(kf):
    with pytest.raises(ValueError) as e:
        kf.predict(X, P, -1.0)
    assert isinstance(e.value, at.ArgusError)
    assert e.value.rust_error == "FilterError::InvalidInterval"
    assert "dt = -1" in str(e.value)


@pytest.mark.parametrize(
    "x, p, needle",
    [
        (X[:3], P, "argument 'x': expected shape (4,), got (3,)"),
        (X, P[:3], "argument 'P': expected shape (4, 4), got (3, 4)"),
        (np.array([1.0, np.nan, 0.0, 0.0]), P, "argument 'x': entry [1] is NaN"),
        (X, np.where(np.eye(4) > 0, P, np.inf), "argument 'P': entry [0, 1] is inf"),
        (X.astype(complex), P, "argument 'x': dtype complex128 is not a real number type"),
        (np.array(["a", "b", "c", "d"]), P, "argument 'x': dtype <U1 is not a real number"),
        (X, -P, "argument 'P': covariance is not positive definite"),
        (X, P + np.triu(np.ones((4, 4)), 1), "argument 'P': covariance is not symmetric"),
    ],
)
def test_bad_arrays_name_argument_index_and_problem(kf, x, p, needle):
    with pytest.raises(InvalidInputError) as e:
        kf.predict(x, p, 1.0)
    assert needle in str(e.value)


def test_non_contiguous_and_integer_arrays_are_read_as_their_values(kf):
    big = np.zeros((4, 8))
    big[:, ::2] = P  # a strided view
    view = big[:, ::2]
    assert not view.flags["C_CONTIGUOUS"]
    a = kf.predict(X, view, 1.0)
    b = kf.predict(X, P, 1.0)
    np.testing.assert_array_equal(a[1], b[1])  # same values, exactly
    c = kf.predict(X.astype(np.int64), P, 1.0)
    np.testing.assert_array_equal(c[0], kf.predict(X.astype(np.int64).astype(float), P, 1.0)[0])
    # Inputs are never written to.
    np.testing.assert_array_equal(big[:, ::2], P)


def test_bad_measurement_and_run_inputs(kf):
    with pytest.raises(InvalidInputError, match=r"argument 'z': expected shape \(2,\), got \(3,\)"):
        kf.update(X, P, np.ones(3))
    t = np.array([0.0, 1.0, 0.5, 2.0])
    z = np.ones((4, 2)) * 1000
    with pytest.raises(
        InvalidInputError,
        match=r"times\[2\] = 0.5 is before times\[1\] = 1 \(time goes backwards\)",
    ):
        kf.run(t, z, X, P)
    with pytest.raises(InvalidInputError, match=r"argument 'plots': 3 rows for 4 times"):
        kf.run(np.arange(4.0), z[:3], X, P)
    z[3, 1] = np.nan
    with pytest.raises(InvalidInputError, match=r"argument 'plots': entry \[3, 1\] is NaN"):
        kf.run(np.arange(4.0), z, X, P)
    with pytest.raises(InvalidInputError, match=r"argument 'P0'"):
        kf.run(np.arange(4.0), np.ones((4, 2)), X, -P)


def test_bad_constructor_arguments():
    with pytest.raises(InvalidInputError, match="argument 'model': unknown motion model \"cw\""):
        at.KalmanFilter("cw", R=R)
    with pytest.raises(InvalidInputError, match="argument 'R'"):
        at.KalmanFilter("cv", R=-R)
    with pytest.raises(InvalidInputError, match="argument 'R': a Cartesian sensor needs R"):
        at.KalmanFilter("cv")
    with pytest.raises(InvalidInputError, match="sigma_range"):
        at.ExtendedKalmanFilter("cv", sigma_azimuth=0.01)
    with pytest.raises(InvalidInputError, match="model"):
        at.KalmanFilter("cv", q=-1.0, R=R)
    with pytest.raises(InvalidInputError, match=r"argument 'transition'"):
        at.Imm([("cv", 1.0), ("cv", 5.0)], [[0.9, 0.2], [0.1, 0.9]], R=R)
    with pytest.raises(InvalidInputError, match=r"models\[1\]"):
        at.Imm([("cv", 1.0), ("xx", 5.0)], np.eye(2), R=R)
    with pytest.raises(InvalidInputError, match=r"argument 'n': 4 noise hypotheses"):
        at.MultiImm([("cv", 1.0)], np.eye(1), sigma_range=50.0, sigma_azimuth=0.001, n=4)
    # The library's mode counts (argus_imm::MAX_PLANAR_MODES = 5, as `argus track`'s IMM):
    # five models are built, six are refused by name.
    five = [("cv", 1.0)] + [("ct", 1.0, w) for w in (0.02, -0.02, 0.05, -0.05)]
    assert at.Imm(five, np.eye(5), R=R).modes == 5
    with pytest.raises(InvalidInputError, match=r"argument 'models': 6 models \(1 to 5 are built\)"):
        at.Imm(five + [("cv", 3.0)], np.eye(6), R=R)


def test_imm_step_errors_name_the_step():
    imm = at.Imm([("cv", 1.0), ("cv", 10.0)], [[0.9, 0.1], [0.1, 0.9]], sigma_range=50.0, sigma_azimuth=0.001)
    plots = np.array([[10_000.0, 0.1], [10_010.0, 0.1], [-5.0, 0.1]])
    with pytest.raises(InvalidInputError, match=r"step 2 \(times\[2\] = 2\)") as e:
        imm.run(np.arange(3.0), plots, X, P)
    assert e.value.rust_error.startswith("SensorError")


def test_unknown_scenario_and_bad_parameter():
    with pytest.raises(UnknownScenarioError) as e:
        at.run_scenario("no-such-scenario", runs=1)
    assert isinstance(e.value, KeyError) and "no-such-scenario" in str(e.value)
    with pytest.raises(InvalidInputError, match="duration"):
        at.run_scenario("cv-polar", runs=1, duration=-5.0)


def test_bad_config_names_line_and_field(root):
    text = (root / "docs/examples/tracker.toml").read_text().replace("max_speed = 350.0", "max_speed = -1.0")
    plots = _two_targets(root)
    with pytest.raises(InvalidInputError) as e:
        at.track(plots, text)
    msg = str(e.value)
    assert msg.startswith("config.toml:") and "max_speed" in msg, msg


def _two_targets(root):
    import csv

    with open(root / "docs/examples/two-targets.csv") as f:
        rows = list(csv.DictReader(f))
    dt = [("t", "f8"), ("sensor", "i8"), ("range", "f8"), ("azimuth", "f8")]
    return np.array([tuple(float(r[k]) if k != "sensor" else int(r[k]) for k, _ in dt) for r in rows], dtype=dt)


def test_bad_plots_name_line_and_field_and_leave_the_tracker_unchanged(root):
    plots = _two_targets(root)
    config = str(root / "docs/examples/tracker.toml")
    tracker = at.Tracker(config)
    times = np.unique(plots["t"])
    first = tracker.process(plots[plots["t"] == times[0]])
    bad = plots[plots["t"] == times[1]].copy()
    bad["range"][1] = -3.0
    with pytest.raises(InvalidInputError) as e:
        tracker.process(bad)
    assert "plots:3: field 'range'" in str(e.value), str(e.value)
    # The tracker is as it was: the rest of the stream gives track()'s rows.
    rest = [tracker.process(plots[plots["t"] == t]) for t in times[1:]]
    whole = at.track(plots, config)
    streamed = np.concatenate([first, *rest])
    assert streamed.dtype == whole.dtype
    for name in whole.dtype.names:
        np.testing.assert_array_equal(streamed[name], whole[name], err_msg=name)
