"""Fixtures: the ``tvf`` binary of this checkout (built by ``cargo test --workspace --release``
or ``cargo build --release -p tvf-cli``; ``TVF_BIN`` overrides), and generated meshes."""

import os
import pathlib
import signal
import subprocess

import pytest

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def tvf_bin():
    path = pathlib.Path(os.environ.get("TVF_BIN", REPOSITORY / "target" / "release" / "tvf"))
    if not path.exists():
        raise RuntimeError(f"the tvf binary is missing at {path}: run `cargo build --release -p tvf-cli` (or set TVF_BIN)")
    return path


@pytest.fixture
def run_tvf(tvf_bin, tmp_path_factory):
    """Runs the tvf command line; returns the CompletedProcess (text). Its default basis cache
    (the user's cache folder) is in the tests' temporary folder, not the home folder."""
    environment = {**os.environ, "XDG_CACHE_HOME": str(tmp_path_factory.getbasetemp() / "xdg-cache")}

    def run(*args, check=True):
        result = subprocess.run([str(tvf_bin), *map(str, args)], capture_output=True, text=True, env=environment)
        if check and result.returncode != 0:
            raise AssertionError(f"tvf {' '.join(map(str, args))} failed: {result.stderr}")
        return result

    return run


@pytest.fixture
def sigint_raises_keyboard_interrupt():
    """Python's own SIGINT handler for the test: a shell starts background jobs with SIGINT
    ignored, and Python then never installs the handler that raises ``KeyboardInterrupt``, so the
    interrupt tests would measure the shell instead of tvf."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)
