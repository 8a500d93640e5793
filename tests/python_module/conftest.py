"""pytest set-up of the Python module's tests (tests/python_module, CTest
python_module): the module is imported from the build tree (PYTHONPATH set by
CTest to <build>/python), the lgi executable is $LGI_EXECUTABLE, temporary
files go under $LGI_TEST_TMPDIR/python_module (the build tree), never into the
source tree."""
import os
import sys

import pytest

sys.dont_write_bytecode = True

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(SOURCE, "experiments", "scenes")


def pytest_configure(config):
    base = os.environ.get("LGI_TEST_TMPDIR")
    if base and not config.option.basetemp:
        config.option.basetemp = os.path.join(base, "python_module")


@pytest.fixture(scope="session")
def lgi_exe():
    exe = os.environ.get("LGI_EXECUTABLE")
    if not exe or not os.access(exe, os.X_OK):
        pytest.skip("LGI_EXECUTABLE is not set to the lgi executable")
    return exe


@pytest.fixture(scope="session")
def scene_path():
    return lambda name: os.path.join(SCENES, name)
