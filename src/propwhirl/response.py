"""Compatibility: `propwhirl.response` moved to :mod:`propwhirl.analysis.response`, its thesis
tables to :mod:`propwhirl.reproduce.ch09` (kept for users' scripts)."""
from propwhirl.analysis.response import *  # noqa: F401,F403
from propwhirl.reproduce.ch09 import THESIS_RESPONSE_SPEEDS, baseline_propeller_responses  # noqa: F401
