"""Shared fixtures of the Python tests, and the rule that an empty or partly skipped run fails.

ctest runs pytest with PYTHONPATH=build/python, OCEANREF_CLI (the built `oceanref` program, for
the comparisons with the command line) and OCEANREF_SOURCE_DIR (the repository).
"""

import csv
import io
import json
import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("OCEANREF_SOURCE_DIR", Path(__file__).resolve().parents[2]))


def _cli_path():
    path = os.environ.get("OCEANREF_CLI", str(SOURCE_DIR / "build" / "src" / "oceanref"))
    if not Path(path).is_file():
        raise RuntimeError(f"the oceanref program is not at {path}: set OCEANREF_CLI")
    return path


@pytest.fixture(scope="session")
def cli():
    """Runs `oceanref ARGS…`; returns stdout (fails the test on a non-zero exit)."""
    program = _cli_path()

    def run(*args, expect=0):
        r = subprocess.run([program, *map(str, args)], capture_output=True, text=True)
        assert r.returncode == expect, f"oceanref {' '.join(map(str, args))}: {r.stderr}"
        return r.stdout

    return run


def csv_rows(text):
    return list(csv.DictReader(io.StringIO(text)))


@pytest.fixture(scope="session")
def manifest():
    with open(SOURCE_DIR / "reference" / "golden" / "manifest.json") as f:
        return {e["name"]: e for e in json.load(f)["entries"]}


@pytest.fixture(scope="session")
def golden_hashes():
    """False when tools/mutation.py runs the tests without the golden hashes
    (OCEANREF_TESTS_NO_GOLDENS=1): the comparisons with the manifest are then left out."""
    return os.environ.get("OCEANREF_TESTS_NO_GOLDENS") != "1"


@pytest.fixture(scope="session")
def golden_scene():
    return lambda name: SOURCE_DIR / "reference" / "scenes" / "golden" / f"{name}.json"


# A run that collects nothing or skips anything fails: every test here must run wherever
# tools/setup.sh has run (it installs everything they need), so a skip means a lost test.
def pytest_sessionfinish(session, exitstatus):
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    skipped = len(reporter.stats.get("skipped", [])) if reporter else 0
    if session.testscollected == 0 or skipped > 0:
        if reporter:
            reporter.write_line(f"oceanref: {session.testscollected} tests collected, {skipped} "
                                "skipped: an empty or partly skipped run fails", red=True)
        session.exitstatus = 1
