"""Shared test configuration."""
import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

from hypothesis import settings  # noqa: E402

settings.register_profile("propwhirl", max_examples=40, deadline=None)
settings.load_profile("propwhirl")
