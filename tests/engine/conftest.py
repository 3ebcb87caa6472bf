"""Fixtures shared by the engine tests."""
from __future__ import annotations

import numpy as np
import pytest

from propwhirl.engine import analyse
from propwhirl.model.statespace import second_order_labels

from helpers.engine_systems import section


@pytest.fixture(scope="module")
def section_analysis():
    fn, mck, VD = section()
    an = analyse(fn, np.arange(1.0, 61.0, 5.0), n_dof=2,
                 state_labels=second_order_labels(["h", "alpha"]), xtol=1e-3)
    return fn, mck, VD, an
