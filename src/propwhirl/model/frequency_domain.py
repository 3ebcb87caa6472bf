"""Frequency-domain (exact Theodorsen) matrices of the typical section for the p-k method.

For harmonic motion at the reduced frequency k = ω b / V, Theodorsen's loads (thesis eq.
7.24–7.27, 7.64–7.66) with the exact C(k) = F(k) + iG(k) (eq. 4.31) are
Q = M_a q̈ + C_a(k) q̇ + K_a(k) q; the matrices are generated from ``derivations/strip_aero.py``
(``strip_aero.theodorsen_blocks``), the structure from ``derivations/typical_section.py``.
The p-k solution itself is :mod:`propwhirl.analysis.pk`.
"""
from __future__ import annotations

import numpy as np

from propwhirl import validate as v
from propwhirl.model.theodorsen import theodorsen

#: reduced frequency used for a (numerically) non-oscillatory root: G(k)/k is singular at 0
K_MIN = 1e-6


def check_section(model) -> None:
    """InputError unless `model` is a TypicalSection with its aerodynamics on."""
    from propwhirl.model.systems import TypicalSection

    if not isinstance(model, TypicalSection) or not model.aero:
        raise v.InputError(f"model = {model!r:.60} is invalid for the p-k method: must be a "
                           "TypicalSection with aero = True")


def section_structure(model) -> tuple[np.ndarray, np.ndarray]:
    """Structural mass [kg/m, kg, kg m] and stiffness [h, α] of a typical section."""
    from propwhirl.generated import typical_section

    S = model.m * model.x_alpha * model.b
    I = model.m * (model.r_alpha * model.b) ** 2
    blk = typical_section.blocks(m=model.m, S=S, I_alpha=I, K_h=model.m * model.omega_h**2,
                                 K_alpha=I * model.omega_alpha**2)
    return np.asarray(blk["mass"], float), np.asarray(blk["stiffness"], float)


def section_pk_matrices(model, V: float, k: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(M, C, K) of M q̈ + C q̇ + K q = 0 for the section at airspeed V [m/s] with the exact
    Theodorsen loads at the reduced frequency k [-] (k below :data:`K_MIN` is raised to it)."""
    from propwhirl.generated import strip_aero

    k = max(float(k), K_MIN)
    C = complex(theodorsen(k))
    aero = strip_aero.theodorsen_blocks(rho=model.flight.density, V=V, b=model.b, a=model.a,
                                        Cla=model.Cla, ac=model.ac, k=k, F=C.real, G=C.imag)
    Ms, Ks = section_structure(model)
    return Ms - aero["theodorsen_M"], -aero["theodorsen_C"], Ks - aero["theodorsen_K"]
