"""Compatibility: `propwhirl.assembly` moved to :mod:`propwhirl.model.assembly` (kept for users' scripts)."""
from propwhirl.model.assembly import *  # noqa: F401,F403
