import os

# One thread per test process: pytest-xdist already runs a process per core, and torch's
# (and the BLAS libraries') own thread pools on top of that oversubscribe the cores many
# times over. Set before anything imports torch or numpy; worker processes inherit it.
for _var in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
# Ray (the RLlib tests) takes the loopback address for its nodes instead of the machine's
# network address, so that every connection of a test cluster stays on this machine.
os.environ.setdefault("RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER", "0")
os.environ.setdefault("SDL_AUDIODRIVER", "dummy")

import pytest  # noqa: E402
from hypothesis import settings  # noqa: E402

# Property tests draw the same examples on every run (reproducible CI); set
# HYPOTHESIS_PROFILE=explore to search with fresh random examples.
settings.register_profile("ci", derandomize=True, database=None, print_blob=True)
settings.register_profile("explore", max_examples=500)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

from worlds import make_world, park  # noqa: E402


@pytest.fixture
def world():
    return park(make_world())


@pytest.fixture
def no_hang():
    """Fail a test that runs over 120 s (with a TimeoutError where it is stuck) instead of
    hanging the suite: for the tests of faults, whose failure mode is a hang."""
    import signal

    def expired(*_):
        raise TimeoutError("the test hung for 120 s")

    old = signal.signal(signal.SIGALRM, expired)
    signal.alarm(120)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, old)
