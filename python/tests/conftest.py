"""Shared fixtures: the repository root and the `argus` binary of the same checkout
(`cargo xtask test` builds it and passes its path in ARGUS_BIN)."""

from __future__ import annotations

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> pathlib.Path:
    return ROOT


@pytest.fixture(scope="session")
def argus_bin() -> str:
    path = os.environ.get("ARGUS_BIN")
    if not path:
        target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
        path = str(target / "debug" / "argus")
    assert os.path.exists(path), f"the argus binary is needed for the CLI comparisons: {path}"
    return path


@pytest.fixture(scope="session")
def run_cli(argus_bin):
    def run(*args: str) -> str:
        done = subprocess.run([argus_bin, *args], capture_output=True, text=True, check=False)
        assert done.returncode == 0, done.stderr
        return done.stdout

    return run
