"""Compatibility: `propwhirl.vibration` moved to :mod:`propwhirl.analysis.vibration` (kept for users' scripts)."""
from propwhirl.analysis.vibration import *  # noqa: F401,F403
