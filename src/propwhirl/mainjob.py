"""Compatibility: `propwhirl.mainjob` (the main analysis of `make run`) moved to
:mod:`propwhirl.app.run` (kept for users' scripts)."""
from propwhirl.app.run import *  # noqa: F401,F403
