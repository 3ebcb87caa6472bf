"""Oracle: the generated in-plane bending matrices against hand-derived ones (issue 14).

Independent of SymPy: the in-plane element is typed from the Hermite-cubic integrals (the
consistent mass of a beam, the rotary-inertia matrix of a Rayleigh beam, the bending
stiffness with EI_chordwise); the propeller–node coupling is typed from the kinetic energy of
the module docstring of derivations/prop_flexwing_inplane.py, and its aerodynamic matrices are
rebuilt numerically here from the hub loads (4.25), the effective angles and the virtual work
(one unit acceleration, rate or displacement at a time).
"""
from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from propwhirl.generated import beam_inplane as gb
from propwhirl.generated import prop_flexwing as g8
from propwhirl.generated import prop_flexwing_inplane as gi

SETTINGS = settings(max_examples=40, deadline=None)
DERIVS = tuple(f"{c}_{v}" for c in ("CZ", "Cm", "CY", "Cn") for v in ("theta", "psi", "q", "r"))


def fl(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False, allow_subnormal=False)


def strat(**ranges) -> st.SearchStrategy[dict]:
    return st.fixed_dictionaries({k: fl(*v) for k, v in ranges.items()})


# ----------------------------------------------------------------------------- element
def mass_oracle(l, m, rIz):
    """Consistent mass m l/420 [...] plus rotary inertia ρI_z/(30 l) [...] on [v1, χ1, v2, χ2]."""
    Mt = m * l / 420 * np.array([
        [156, 22 * l, 54, -13 * l],
        [22 * l, 4 * l**2, 13 * l, -3 * l**2],
        [54, 13 * l, 156, -22 * l],
        [-13 * l, -3 * l**2, -22 * l, 4 * l**2],
    ])
    Mr = rIz / (30 * l) * np.array([
        [36, 3 * l, -36, 3 * l],
        [3 * l, 4 * l**2, -3 * l, -l**2],
        [-36, -3 * l, 36, -3 * l],
        [3 * l, -l**2, -3 * l, 4 * l**2],
    ])
    return Mt + Mr


def stiffness_oracle(l, EIc):
    return EIc / l**3 * np.array([
        [12, 6 * l, -12, 6 * l],
        [6 * l, 4 * l**2, -6 * l, 2 * l**2],
        [-12, -6 * l, 12, -6 * l],
        [6 * l, 2 * l**2, -6 * l, 4 * l**2],
    ])


@given(l=fl(0.05, 20.0), m=fl(1e-2, 1e3), rIz=fl(0.0, 1e2))
def test_inplane_mass(l, m, rIz):
    M = gb.inplane_mass(l, m, rIz)
    scale = (m * l + rIz / l) * max(l, 1.0) ** 2
    np.testing.assert_allclose(M, mass_oracle(l, m, rIz), rtol=1e-12, atol=1e-13 * scale)


@given(l=fl(0.05, 20.0), EIc=fl(1e-2, 1e12))
def test_inplane_stiffness(l, EIc):
    np.testing.assert_allclose(gb.inplane_stiffness(l, EIc), stiffness_oracle(l, EIc),
                               rtol=1e-12)


def test_block_function_equals_the_matrices():
    out = gb.inplane_blocks(length=0.3, m=2.0, rho_Iz=0.4, EI_chordwise=5e5)
    np.testing.assert_array_equal(out["inplane_mass"], gb.inplane_mass(0.3, 2.0, 0.4))
    np.testing.assert_array_equal(out["inplane_stiffness"], gb.inplane_stiffness(0.3, 5e5))


# ----------------------------------------------------------------------------- propeller node
STRUCT = strat(M_P=(0.1, 100.0), S_theta_P=(-50.0, 50.0), I_theta_P=(0.1, 100.0),
               I_psi_P=(0.1, 100.0), S_alpha_P=(-50.0, 50.0), I_alpha_P=(0.1, 100.0),
               I_theta_alpha_P=(-50.0, 50.0), I_chi_P=(0.1, 100.0),
               I_psi_chi_P=(-50.0, 50.0), I_Omega=(1e-3, 5.0), Omega=(-400.0, 400.0))


@SETTINGS
@given(p=STRUCT)
def test_structure_blocks(p):
    """Rows/columns [θ, ψ | h, α, v, χ]; T_P + ½ I_Ω (Ω + (θ̇ + α̇) sin(ψ + χ))²."""
    out = gi.structure_blocks(**{k: p[k] for k in gi.BLOCKS["structure_blocks"][0]})
    G = p["I_Omega"] * p["Omega"]
    Bs = np.array([[p["S_theta_P"], p["I_theta_alpha_P"], 0, 0],
                   [0, 0, 0, p["I_psi_chi_P"]]])
    Gs = np.array([[p["M_P"], p["S_alpha_P"], 0, 0], [p["S_alpha_P"], p["I_alpha_P"], 0, 0],
                   [0, 0, p["M_P"], 0], [0, 0, 0, p["I_chi_P"]]])
    Ds = np.array([[0, 0, 0, G], [0, -G, 0, 0]])      # θ row: +G(ψ̇+χ̇); ψ row: −G(θ̇+α̇)
    Hs = np.array([[0, 0], [0, G], [0, 0], [-G, 0]])   # α row: +G ψ̇; χ row: −G θ̇
    Js = np.array([[0, 0, 0, 0], [0, 0, 0, G], [0, 0, 0, 0], [0, -G, 0, 0]])
    for name, want in (("Bs", Bs), ("Fs", Bs.T), ("Gs", Gs), ("Ds", Ds), ("Hs", Hs),
                       ("Js", Js)):
        np.testing.assert_allclose(np.broadcast_to(out[name], want.shape), want, rtol=1e-13,
                                   atol=1e-13 * (1 + abs(G)), err_msg=name)


def inertia_oracle(Mp, S_psi, I_psi, l_psi, ab):
    d = l_psi - ab
    return I_psi + 2 * d * S_psi + d**2 * Mp, I_psi + d * S_psi


@given(m=st.lists(fl(0.1, 50.0), min_size=1, max_size=4),
       x=st.lists(fl(-3.0, 1.0), min_size=4, max_size=4), l_psi=fl(-2.0, 0.5),
       ab=fl(-0.5, 0.5))
def test_inplane_inertia_from_point_masses(m, x, l_psi, ab):
    """I_χ,P = Σ m (x − ab)², I_ψχ,P = Σ m (x − l_ψ)(x − ab) from the pivot values."""
    m, x = np.array(m), np.array(x[:len(m)])
    got = gi.inplane_inertia(m.sum(), np.sum(m * (x - l_psi)), np.sum(m * (x - l_psi) ** 2),
                             l_psi, ab)[:, 0]
    want = (np.sum(m * (x - ab) ** 2), np.sum(m * (x - l_psi) * (x - ab)))
    np.testing.assert_allclose(got, want, rtol=1e-10, atol=1e-10 * np.sum(m) * 16)


AERO = strat(e_theta=(-3.0, 1.0), e_psi=(-3.0, 1.0), e_alpha=(-3.0, 1.0), rho=(0.05, 1.5),
             V=(1.0, 300.0), R=(0.1, 3.0), **{d: (-3.0, 3.0) for d in DERIVS})


def generalised_forces(p, q, qd, qdd):
    """Q on [θ, ψ, h, α, v, χ] for one state, from (4.25) with the effective angles
    θ̄ = θ + α + ż_hub/V, ψ̄ = ψ + χ − ẏ_hub/V, z_hub = h + e_α α + e_θ θ,
    y_hub = −e_ψ ψ − e_α χ, and δW of the module docstring."""
    th, ps, h, al, v, ch = q
    thd, psd, hd, ald, vd, chd = qd
    thdd, psdd, hdd, aldd, vdd, chdd = qdd
    V, R, ea, et, ep = p["V"], p["R"], p["e_alpha"], p["e_theta"], p["e_psi"]
    tb = th + al + (hd + ea * ald + et * thd) / V
    pb = ps + ch + (ep * psd + ea * chd) / V
    tbd = thd + ald + (hdd + ea * aldd + et * thdd) / V
    pbd = psd + chd + (ep * psdd + ea * chdd) / V
    S = np.pi * R**2
    k1, k2 = 0.5 * p["rho"] * V**2 * S, p["rho"] * V**2 * S * R

    def combo(c):
        return (p[f"{c}_theta"] * tb + p[f"{c}_psi"] * pb + p[f"{c}_q"] * tbd * R / V
                + p[f"{c}_r"] * pbd * R / V)

    FZ, MY, FY, MZ = k1 * combo("CZ"), k2 * combo("Cm"), k1 * combo("CY"), k2 * combo("Cn")
    return np.array([MY + et * FZ, MZ - ep * FY, FZ, MY + ea * FZ, 0.0, MZ - ea * FY])


@SETTINGS
@given(p=AERO)
def test_aero_blocks(p):
    out = gi.aero_blocks(**{k: p[k] for k in gi.BLOCKS["aero_blocks"][0]})
    z, eye = np.zeros(6), np.eye(6)
    Ma = np.column_stack([generalised_forces(p, z, z, eye[j]) for j in range(6)])
    Ca = np.column_stack([generalised_forces(p, z, eye[j], z) for j in range(6)])
    Ka = np.column_stack([generalised_forces(p, eye[j], z, z) for j in range(6)])
    P, W = slice(0, 2), slice(2, 6)
    want = dict(Ba=Ma[P, W], Da=Ca[P, W], Fa=Ka[P, W], P1=Ma[W, P], P2=Ma[W, W],
                P3=Ca[W, P], P4=Ca[W, W], P5=Ka[W, P], P6=Ka[W, W])
    scale = p["rho"] * p["V"] ** 2 * p["R"] ** 3 * 100
    for name, w in want.items():
        np.testing.assert_allclose(np.broadcast_to(out[name], w.shape), w, rtol=1e-11,
                                   atol=1e-12 * scale, err_msg=name)
    # the θ–ψ blocks this module does not generate are chapter 8's: check them too
    ch8 = g8.aero_blocks(**{k: p[k] for k in g8.BLOCKS["aero_blocks"][0]})
    for name, w in (("Aa", Ma[P, P]), ("Ca", Ca[P, P]), ("Ea", Ka[P, P])):
        np.testing.assert_allclose(np.broadcast_to(ch8[name], w.shape), w, rtol=1e-11,
                                   atol=1e-12 * scale, err_msg=name)


def test_generated_derivative_functions_exist():
    """The generator's `_d` functions cover the new block functions."""
    for mod, names in ((gb, ("inplane_blocks_d",)),
                       (gi, ("structure_blocks_d", "aero_blocks_d", "inplane_inertia_d"))):
        for n in names:
            assert n in mod.PARTIALS
    d = gb.inplane_blocks_d(length=0.5, m=2.0, rho_Iz=0.3, EI_chordwise=1e4)
    np.testing.assert_allclose(d["inplane_stiffness"]["EI_chordwise"],
                               stiffness_oracle(0.5, 1.0), rtol=1e-13)
