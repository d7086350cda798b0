"""Where the Python tests find the module, the program and the data.

ctest runs them (tests/CMakeLists.txt) with PYTHONPATH=build/python and
DFRECON_CLI, DFRECON_SOURCE and DFRECON_FIXTURES set; run by hand:

    PYTHONPATH=build/python DFRECON_CLI=build/bin/dfrecon python3 -m pytest tests/python
"""
import json
import os
import pathlib
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("DFRECON_SOURCE", pathlib.Path(__file__).parents[2]))
CLI = os.environ.get("DFRECON_CLI", str(SOURCE / "build" / "bin" / "dfrecon"))
FIXTURES = pathlib.Path(os.environ.get("DFRECON_FIXTURES", SOURCE / "build" / "fixtures"))
SHARED = SOURCE.parent / "shared" / "data"


def run_cli(*args):
    """Runs the program, returns its --json report (stdout) as a dict."""
    out = subprocess.run([CLI, "--quiet", *map(str, args)], check=True, capture_output=True,
                         text=True)
    return json.loads(out.stdout)


@pytest.fixture(scope="session")
def cli():
    return run_cli


@pytest.fixture(scope="session")
def examples():
    return SOURCE / "examples"


@pytest.fixture(scope="session")
def fixtures():
    return FIXTURES


@pytest.fixture(scope="session")
def shared():
    return SHARED
