"""Compatibility: `propwhirl.statespace` moved to :mod:`propwhirl.model.statespace` (kept for users' scripts)."""
from propwhirl.model.statespace import *  # noqa: F401,F403
