"""pytest set-up of the command tests (tests/commands): temporary files go under
$LGI_TEST_TMPDIR/commands_pytest (the build tree under CTest), never into the
source tree; no bytecode is written beside the scripts."""
import os
import sys

sys.dont_write_bytecode = True


def pytest_configure(config):
    base = os.environ.get("LGI_TEST_TMPDIR")
    if base and not config.option.basetemp:
        # pytest empties its basetemp at start: a folder of its own, not the shared tmp.
        config.option.basetemp = os.path.join(base, "commands_pytest")
