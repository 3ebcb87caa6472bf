"""Oracle: the generated loads of a propeller rigid on a hub point (derivations/prop_hub.py,
issue 22) against the hub loads (4.25) rebuilt numerically here — one unit displacement, rate
or acceleration of the hub at a time — and, through the generated hub motion, against the
chapter-8 propeller with in-plane bending (every aerodynamic and gyroscopic block)."""
from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.generated import prop_flexwing as g8
from propwhirl.generated import prop_flexwing_inplane as gi
from propwhirl.generated import prop_hub as gh

DERIVS = tuple(f"{c}_{v}" for c in ("CZ", "Cm", "CY", "Cn") for v in ("theta", "psi", "q", "r"))
fl = lambda lo, hi: st.floats(lo, hi, allow_nan=False, allow_subnormal=False)  # noqa: E731
VALUES = st.fixed_dictionaries(dict(
    rho=fl(0.3, 1.3), V=fl(10, 300), R=fl(0.3, 3), I_Omega=fl(0.1, 50), Omega=fl(-300, 300),
    e_theta=fl(-2, 2), e_psi=fl(-2, 2), e_alpha=fl(-2, 2),
    **{d: fl(-3, 3) for d in DERIVS}))


def hub_loads(p, tb, pb, tb_dot, pb_dot):
    """[F_Z, F_Y, M_Y, M_Z] of (4.25) at effective angles and their rates (order of u)."""
    S = np.pi * p["R"] ** 2
    k1, k2 = p["rho"] * p["V"] ** 2 * S / 2, p["rho"] * p["V"] ** 2 * S * p["R"]
    c = lambda n: (p[f"{n}_theta"] * tb + p[f"{n}_psi"] * pb                 # noqa: E731
                   + (p[f"{n}_q"] * tb_dot + p[f"{n}_r"] * pb_dot) * p["R"] / p["V"])
    return np.array([k1 * c("CZ"), k1 * c("CY"), k2 * c("Cm"), k2 * c("Cn")])


def oracle(p):
    """(Ma, Ca, Ka, Cg) on u = [z, y, θ, ψ]: θ̄ = θ + ż/V, ψ̄ = ψ − ẏ/V (8.26)."""
    V = p["V"]
    Ma, Ca, Ka = (np.zeros((4, 4)) for _ in range(3))
    for j in range(4):
        e = np.eye(4)[j]
        Ka[:, j] = hub_loads(p, e[2], e[3], 0, 0)
        Ca[:, j] = hub_loads(p, e[0] / V, -e[1] / V, e[2], e[3])
        Ma[:, j] = hub_loads(p, 0, 0, e[0] / V, -e[1] / V)
    Cg = np.zeros((4, 4))
    Cg[2, 3], Cg[3, 2] = p["I_Omega"] * p["Omega"], -p["I_Omega"] * p["Omega"]
    return Ma, Ca, Ka, Cg


@settings(max_examples=40, deadline=None)
@given(VALUES)
def test_the_hub_blocks_are_the_hub_loads_of_4_25(p):
    b = gh.hub_blocks(**{k: p[k] for k in gh.BLOCKS["hub_blocks"][0]})
    for got, want in zip((b["Ma_hub"], b["Ca_hub"], b["Ka_hub"], b["Cg"]), oracle(p)):
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12 * (1 + np.abs(want).max()))


@settings(max_examples=40, deadline=None)
@given(VALUES)
def test_through_the_hub_motion_they_are_chapter_8s_with_in_plane_bending(p):
    G = gh.hub_motion(p["e_theta"], p["e_psi"], p["e_alpha"])
    b = gh.hub_blocks(**{k: p[k] for k in gh.BLOCKS["hub_blocks"][0]})
    aero = {k: p[k] for k in gi.BLOCKS["aero_blocks"][0]}
    a8 = g8.aero_blocks(**{k: p[k] for k in g8.BLOCKS["aero_blocks"][0]})
    ai = gi.aero_blocks(**aero)
    si = gi.structure_blocks(**{k: (p[k] if k in p else 1.0)
                                for k in gi.BLOCKS["structure_blocks"][0]})
    s8 = g8.structure_blocks(**{k: (p[k] if k in p else (0.0 if k.startswith("zeta") else 1.0))
                                for k in g8.BLOCKS["structure_blocks"][0]})
    full = lambda pp, pw, wp, ww: np.block([[pp, pw], [wp, ww]])              # noqa: E731
    refs = [full(a8["Aa"], ai["Ba"], ai["P1"], ai["P2"]),
            full(a8["Ca"], ai["Da"], ai["P3"], ai["P4"]),
            full(a8["Ea"], ai["Fa"], ai["P5"], ai["P6"]),
            full(s8["Cs_viscous"], si["Ds"], si["Hs"], si["Js"])]
    for hub, ref in zip((b["Ma_hub"], b["Ca_hub"], b["Ka_hub"], b["Cg"]), refs):
        np.testing.assert_allclose(G.T @ hub @ G, ref, rtol=1e-10,
                                   atol=1e-10 * (1 + np.abs(ref).max()))
