"""Compatibility: `propwhirl.stability` (the eigenvalue tracking engine) moved to
:mod:`propwhirl.engine`, its state-space helpers to :mod:`propwhirl.model.statespace` and its
whirl classification to :mod:`propwhirl.analysis.whirl` (kept for users' scripts)."""
from propwhirl.analysis.whirl import (content, dominant, orbit_signed_area,  # noqa: F401
                                      rotation_sign_from_gyroscopic, whirl_sense)
from propwhirl.engine import *  # noqa: F401,F403
from propwhirl.engine.eigensolve import StateMatrixFn  # noqa: F401
from propwhirl.model.statespace import second_order_labels, state_matrix_from_mck  # noqa: F401
