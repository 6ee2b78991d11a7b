# Paths come from ctest (python/CMakeLists.txt): TMDEM_SOURCE_DIR, TMDEM_BINARY, and PYTHONPATH
# holding the built module. Missing settings are errors, never skips.
import os
import pathlib

import pytest


def _required(name):
    value = os.environ.get(name)
    if not value:
        raise RuntimeError(f"{name} is not set; run these tests through ctest (label python)")
    return pathlib.Path(value)


@pytest.fixture(scope="session")
def source_dir():
    return _required("TMDEM_SOURCE_DIR")


@pytest.fixture(scope="session")
def tmdem_binary():
    return _required("TMDEM_BINARY")


@pytest.fixture(scope="session")
def lattice_scene(source_dir):
    return source_dir / "examples" / "lattice_constant.toml"
