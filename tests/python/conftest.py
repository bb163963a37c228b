"""Fixtures of the Python package's tests (run by ctest, label python; tests/python/CMakeLists.txt).

The package is imported from the build tree (PYTHONPATH=<build>/python, set by ctest);
MERIDIAN_CLI names the `meridian` executable of the same build, the reference the
arrays are compared with. Nothing is skipped: a missing numpy, dask or reference
tool fails the test.
"""

import os
import pathlib
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Run the CLI: cli(*args, input=None) -> CompletedProcess (text; raises if it fails)."""
    exe = os.environ.get("MERIDIAN_CLI")
    assert exe and os.access(exe, os.X_OK), "MERIDIAN_CLI must name the meridian executable (ctest sets it)"

    def run(*args, input=None, check=True):
        return subprocess.run([exe, *map(str, args)], input=input, capture_output=True, text=True, check=check)

    return run


@pytest.fixture(scope="session")
def source_dir():
    d = os.environ.get("MERIDIAN_SOURCE_DIR")
    return pathlib.Path(d) if d else pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def synth_files(tmp_path_factory, cli):
    """The synthetic model of degree 60, seed 3 written by the CLI: dir / m.egm, m.egm.cof, m.gfc."""
    d = tmp_path_factory.mktemp("model")
    cli("gravity", "synth-model", "--degree", 60, "--seed", 3, "--out", d / "m")
    return d


@pytest.fixture(scope="session")
def read_csv():
    """read_csv(path) -> numpy structured array of a CSV the CLI wrote: `#` comment lines
    skipped, the header's names as field names ("time [s]" → "time_s"), empty fields NaN."""
    import io

    import numpy as np

    def read(path):
        text = "".join(ln for ln in open(path, encoding="utf-8") if not ln.lstrip().startswith("#"))
        return np.genfromtxt(io.StringIO(text), delimiter=",", names=True, dtype=np.float64,
                             deletechars="[]", missing_values="", filling_values=np.nan)

    return read
