"""Shared test configuration."""
import os
import sys
from pathlib import Path

# test helpers (brute-force oracles, shared fixtures) import as `helpers.<module>`
sys.path.insert(0, str(Path(__file__).resolve().parent))

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import pytest  # noqa: E402
from hypothesis import settings  # noqa: E402

settings.register_profile("propwhirl", max_examples=40, deadline=None)
settings.load_profile("propwhirl")


@pytest.fixture(scope="session")
def reproduction_records():
    """The whole thesis reproduction (every registered case, 2 processes), computed once per
    test session and shared by the harness, chapter and README tests (a tuple: read-only)."""
    from propwhirl.reproduce import harness

    return tuple(harness.run(processes=2))
