"""Compatibility: `propwhirl.wing` moved to :mod:`propwhirl.model.wing` (kept for users' scripts)."""
from propwhirl.model.wing import *  # noqa: F401,F403
