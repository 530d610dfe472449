"""Shared fixtures of the Python tests (run from ctest: PYTHONPATH is the build's python/)."""
import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
MECHANISMS = ROOT / "mechanisms"


@pytest.fixture
def mechanisms():
    return MECHANISMS


@pytest.fixture
def mo2d_cli():
    """The C++ mo2d executable of this build (ctest sets MO2D_CLI)."""
    path = os.environ.get("MO2D_CLI")
    if not path:
        pytest.skip("MO2D_CLI is not set (run from ctest)")
    return path
