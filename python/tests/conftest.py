"""Shared fixtures of the vs11 module's tests: where the source tree and the built tools are."""
import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("VS11_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY_DIR = pathlib.Path(os.environ.get("VS11_BINARY_DIR", SOURCE_DIR / "build"))


@pytest.fixture
def programs_dir():
    return SOURCE_DIR / "programs"


@pytest.fixture
def vs11_tool():
    return BINARY_DIR / "vm" / "vs11"


@pytest.fixture
def irrmap_tool():
    return BINARY_DIR / "irradiance" / "irrmap"
