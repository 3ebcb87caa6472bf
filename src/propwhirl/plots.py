"""Compatibility: `propwhirl.plots` moved to :mod:`propwhirl.app.plots` (kept for users' scripts)."""
from propwhirl.app.plots import *  # noqa: F401,F403
