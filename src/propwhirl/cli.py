"""Compatibility: `propwhirl.cli` (the console script's former `propwhirl.cli:main`) moved to
:mod:`propwhirl.app.cli`, its case library to :mod:`propwhirl.cases.registry` (kept for users'
scripts)."""
from propwhirl.app.cli import *  # noqa: F401,F403
from propwhirl.cases.registry import CASES, case_model  # noqa: F401
