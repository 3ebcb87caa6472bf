"""Compatibility: `propwhirl.aero` moved to :mod:`propwhirl.model.propeller_aero` (kept for users' scripts)."""
from propwhirl.model.propeller_aero import *  # noqa: F401,F403
