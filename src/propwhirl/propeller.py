"""Compatibility: `propwhirl.propeller` moved to :mod:`propwhirl.model.propeller` (kept for users' scripts)."""
from propwhirl.model.propeller import *  # noqa: F401,F403
