"""Chapter 7: the Patil HALE wing's in-vacuo modes, flutter and divergence (Tables 7.2–7.4;
the case is :mod:`propwhirl.cases.ch07_patil`)."""
from __future__ import annotations

import numpy as np

from propwhirl.analysis.stability import first_of_kind, speed_and_frequency
from propwhirl.analysis.vibration import classify_wing_modes
from propwhirl.cases.ch07_patil import patil_model, patil_wing
from propwhirl.reproduce.harness import analyse, register


@register("t7.2")
def table_7_2() -> dict[str, float]:
    """Table 7.2: in-vacuo frequencies [rad/s] of the Patil wing with 3 beam elements."""
    modes = dict(classify_wing_modes(patil_wing(n_elements=3), count=4))
    return {
        "t7.2/first_bending": modes["bending 1"],
        "t7.2/second_bending": modes["bending 2"],
        "t7.2/third_bending": modes["bending 3"],
        "t7.2/first_torsion": modes["torsion 1"],
    }


def _flutter_divergence(prefix: str, lift_slope) -> dict[str, float]:
    a = analyse(patil_model(20, lift_slope))
    Vf, ff = speed_and_frequency(first_of_kind(a, "flutter"))
    Vd, _ = speed_and_frequency(first_of_kind(a, "divergence"))
    return {f"{prefix}/flutter_speed": Vf, f"{prefix}/flutter_frequency": 2 * np.pi * ff,
            f"{prefix}/divergence_speed": Vd}


@register("t7.3")
def table_7_3() -> dict[str, float]:
    """Table 7.3: flutter speed [m/s], frequency [rad/s] and divergence speed, 20 elements."""
    return _flutter_divergence("t7.3", 2 * np.pi)


@register("t7.4")
def table_7_4() -> dict[str, float]:
    """Table 7.4: as 7.3 with the elliptic lift-curve slope 2π√(1 − x²) (eq. 7.81)."""
    return _flutter_divergence("t7.4", "elliptic")
