"""Set-up shared by the Python module's tests: where the module, the command line, the sources and
the shared data are, datasets the command line renders once per session, and the run's verdict:
a run in which no test passed fails, and one in which a test skipped (its shared data is missing)
and none failed exits 77, which ctest reports as skipped (pytest itself exits 0 for both)."""
import json
import os
import pathlib
import subprocess

import pytest

import ladarsim

SOURCE_DIR = pathlib.Path(os.environ.get("LADARSIM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = pathlib.Path(os.environ.get("LADARSIM_CLI", SOURCE_DIR / "build" / "apps" / "ladarsim"))
SHARED_DIR = pathlib.Path(os.environ.get("LADARSIM_SHARED_DIR", SOURCE_DIR.parent / "shared"))
SMALL = SOURCE_DIR / "tests" / "cli" / "small.json"  # 3 frames: a building and an approaching drone


def run_cli(*args):
    """Runs `ladarsim ARGS...`; returns its standard output, failing the test on a non-zero exit."""
    result = subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True)
    assert result.returncode == 0, f"ladarsim {' '.join(map(str, args))}: {result.stderr}"
    return result.stdout


def read_json(path):
    with open(path) as f:
        return json.load(f)


@pytest.fixture(scope="session")
def cli_small(tmp_path_factory):
    """tests/cli/small.json rendered by the command line (its seed, 3 frames, 2 threads)."""
    out = tmp_path_factory.mktemp("cli") / "small"
    run_cli("render", SMALL, "--out", out, "--threads", 2, "--quiet")
    return out


SKIPPED = 77  # the SKIP_RETURN_CODE of tests/CMakeLists.txt
_passed = 0
_skipped = 0


def pytest_report_header(config):
    return f"ladarsim module: {ladarsim.__file__}; command line: {CLI}; shared data: {SHARED_DIR}"


def pytest_runtest_logreport(report):
    global _passed, _skipped
    if report.when == "call" and report.passed:
        _passed += 1
    if report.skipped:
        _skipped += 1


def pytest_sessionfinish(session, exitstatus):
    if exitstatus == 0 and _passed == 0:
        print("\nno test passed (all skipped or none collected): failing the run")
        session.exitstatus = pytest.ExitCode.TESTS_FAILED
    elif exitstatus == 0 and _skipped:
        print(f"\n{_skipped} skipped, none failed: reporting the run as skipped (exit {SKIPPED})")
        session.exitstatus = SKIPPED
