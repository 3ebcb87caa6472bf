"""A modal model's strip aerodynamics and a swept reference axis (issue 36, item 6e): the
strips are an unswept wing's, so wing grids whose line is swept by more than
STRIP_SWEEP_LIMIT_DEG are refused with them, by name, and taken without them."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from propwhirl import InputError
from propwhirl.cases.ch09_baseline import baseline_flight, baseline_wing
from propwhirl.model import ModalPropellerWing, ModalStructure, StripPlanform
from propwhirl.model.modal_structure import STRIP_SWEEP_LIMIT_DEG, reference_sweep


def model(sweep_deg: float, **kw) -> ModalPropellerWing:
    wing = baseline_wing(n_elements=6)
    s = ModalStructure.from_wing(wing, n_modes=4)
    xyz = s.xyz.copy()
    xyz[:, 0] += math.tan(math.radians(sweep_deg)) * xyz[:, 1]
    s = replace(s, xyz=xyz, source="swept modes")
    return ModalPropellerWing(s, tuple(int(g) for g in s.grid_ids), StripPlanform.from_wing(wing),
                              baseline_flight(), **kw)


@pytest.mark.parametrize("sweep", [-25.0, 6.0, 35.0])
def test_the_strips_refuse_a_swept_axis_by_name(sweep):
    with pytest.raises(InputError) as info:
        model(sweep)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"swept modes: wing_grids (GRID 1 to GRID 7) make a reference "
                              f"axis swept by {sweep:.1f} deg, more than the "
                              f"{STRIP_SWEEP_LIMIT_DEG:g} deg the strip aerodynamics take")
    assert "unswept wing's" in message and "doublet lattice" in message


@pytest.mark.parametrize("sweep", [0.0, 4.9, -4.9])
def test_a_few_degrees_are_the_strips_and_the_structure_alone_any(sweep):
    m = model(sweep)
    assert reference_sweep(m.structure, m.wing_grids) == pytest.approx(sweep, abs=1e-12)
    bare = model(35.0, wing_aero=False)
    assert reference_sweep(bare.structure, bare.wing_grids) == pytest.approx(35.0, abs=1e-12)
    with pytest.raises(InputError, match="swept by 35.0 deg"):
        bare.with_(wing_aero=True)
    assert np.all(np.isfinite(bare.state_matrix(np.array([50.0]))))
