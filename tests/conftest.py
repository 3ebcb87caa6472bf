"""Shared test configuration."""
import os
import sys
from pathlib import Path

# test helpers (brute-force oracles, shared fixtures) import as `helpers.<module>`
sys.path.insert(0, str(Path(__file__).resolve().parent))

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

from hypothesis import settings  # noqa: E402

settings.register_profile("propwhirl", max_examples=40, deadline=None)
settings.load_profile("propwhirl")
