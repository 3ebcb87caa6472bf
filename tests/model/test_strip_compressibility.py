"""The Prandtl–Glauert strips (issue 37, item 5; propwhirl.model.aerodynamics.compressibility):
the wing's ``compressibility = "prandtl-glauert"`` divides every strip's lift-curve slope by
β = √(1 − M²) at the Mach of its ``strip_mach`` (fixed, or V/a at each speed), on the
finite-state strips and on the p-k's exact-Theodorsen strips; the default changes nothing."""
import dataclasses

import numpy as np
import pytest

from propwhirl import io
from propwhirl.analysis import analyse
from propwhirl.analysis.pk import pk_sweep
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model.aerodynamics import compressibility as pg
from propwhirl.model.frequency_domain import pk_system
from propwhirl.model.structure.assembly import wing_aero, wing_aero_blocks
from propwhirl.model.structure.wing import Wing
from propwhirl.validate import InputError

WING = dict(semi_span=6.0, mass_per_length=20.0, EI=2.0e5, GJ=1.0e5, radius_of_gyration=0.25,
            root_chord=1.2, tip_chord=0.8, elastic_axis=0.4, aerodynamic_centre=0.25,
            n_elements=6)
RHO, A = 1.1, 330.0


def pg_wing(mach="speed", **kw) -> Wing:
    return Wing(**WING, compressibility="prandtl-glauert", strip_mach=mach, **kw)


def steady_stiffness(blocks) -> np.ndarray:
    """Each strip's steady (k → 0) aerodynamic stiffness [per strip] on its [h, α]: the lag
    states at rest, 0 = Ww w + Wq q, so Q = (Ka − W0 Ww⁻¹ Wq) q."""
    w = -np.linalg.solve(blocks["Ww"], blocks["Wq"])
    return blocks["Ka"] + blocks["W0"] @ w


@pytest.mark.parametrize("aero_model", ["leishman-nguyen", "wagner"])
@pytest.mark.parametrize("mach", [0.3, 0.6, 0.85])
def test_steady_lift_and_moment_scale_by_one_over_beta_exactly(aero_model, mach):
    """Oracle: Theodorsen's steady section loads, by hand — lift per unit span
    L = (2π/β) ρ V² b α at the aerodynamic centre, Q_h = −L, Q_α = L b (a − a_c) — times the
    strip width; the plunge displacement loads nothing."""
    V = np.array([80.0, 150.0])
    wing = pg_wing(mach, aero_model=aero_model)
    K = steady_stiffness(wing_aero_blocks(wing, RHO, V, A))
    K0 = steady_stiffness(wing_aero_blocks(dataclasses.replace(wing, compressibility="none"),
                                           RHO, V, A))
    node = wing.node_properties()
    beta = np.sqrt(1.0 - mach ** 2)
    L = (2 * np.pi / beta) * RHO * V[:, None] ** 2 * node["b"][None, :] * node["width"][None, :]
    np.testing.assert_allclose(K[..., 0, 1], -L, rtol=1e-12)
    np.testing.assert_allclose(K[..., 1, 1], L * node["b"] * (node["a"] - node["ac"]),
                               rtol=1e-12)
    np.testing.assert_allclose(K[..., :, 0], 0.0, atol=1e-9 * np.max(np.abs(L)))
    np.testing.assert_allclose(K[..., :, 1], K0[..., :, 1] / beta, rtol=1e-12)


def test_apparent_mass_unchanged_and_circulation_scaled():
    V = np.array([120.0])
    wing = pg_wing(0.6)
    b = wing_aero_blocks(wing, RHO, V, A)
    b0 = wing_aero_blocks(dataclasses.replace(wing, compressibility="none"), RHO, V, A)
    np.testing.assert_array_equal(b["Ma"], b0["Ma"])          # noncirculatory: no Cla
    np.testing.assert_allclose(b["W0"], b0["W0"] / 0.8, rtol=1e-12)   # Cla ρ V b C(k) w


def test_fixed_mach_is_the_slope_two_pi_over_beta():
    """strip_mach = 0.6 is the wing with C_lα = 2π/0.8 at every speed: the finite-state and the
    exact-Theodorsen (p-k) matrices."""
    V = np.array([60.0, 140.0, 250.0])
    wing = pg_wing(0.6)
    ref = Wing(**WING, lift_slope=2 * np.pi / 0.8)
    got, want = wing_aero(wing, RHO, V), wing_aero(ref, RHO, V)
    for k in ("Ma", "Ca", "Ka", "W0", "Ww", "Wv", "Wq"):
        np.testing.assert_allclose(got[k], want[k], rtol=1e-13, atol=0.0)
    model = wingtip_propeller_wing()
    m_pg = model.with_(wing=dataclasses.replace(model.wing, compressibility="prandtl-glauert",
                                                strip_mach=0.6))
    m_ref = model.with_(wing=dataclasses.replace(model.wing, lift_slope=2 * np.pi / 0.8))
    for omega in (1.0, 40.0):
        for x, y in zip(pk_system(m_pg, 200.0)(omega), pk_system(m_ref, 200.0)(omega)):
            np.testing.assert_allclose(x, y, rtol=1e-12, atol=1e-9)
    # and the incompressible matrices differ (the option does something)
    assert not np.allclose(pk_system(model, 200.0)(40.0)[2], pk_system(m_pg, 200.0)(40.0)[2])


def test_matched_mach_is_v_over_a_at_each_speed():
    V = np.array([50.0, 150.0, 280.0])
    wing = pg_wing("speed")
    got = wing_aero(wing, RHO, V, A)
    for i, Vi in enumerate(V):
        ref = Wing(**WING, lift_slope=2 * np.pi / np.sqrt(1 - (Vi / A) ** 2))
        want = wing_aero(ref, RHO, np.array([Vi]))
        for k in ("Ka", "Ca", "W0"):
            np.testing.assert_allclose(got[k][i], want[k][0], rtol=1e-13)
    np.testing.assert_allclose(pg.lift_slope_factor(wing, V, A),
                               1 / np.sqrt(1 - (V / A) ** 2), rtol=1e-15)
    # the default is incompressible: no factor, the wing's own slopes
    assert pg.lift_slope_factor(Wing(**WING), V, A) is None


def test_default_wing_is_unchanged_bit_for_bit():
    V = np.array([10.0, 200.0])
    model = wingtip_propeller_wing()
    explicit = model.with_(wing=dataclasses.replace(model.wing, compressibility="none",
                                                    strip_mach=0.5))
    np.testing.assert_array_equal(model.state_matrix(V), explicit.state_matrix(V))


def test_matched_mach_beyond_the_limit_is_refused_in_one_line():
    model = wingtip_propeller_wing()
    m = model.with_(wing=dataclasses.replace(model.wing, compressibility="prandtl-glauert"))
    a = model.flight.speed_of_sound
    with pytest.raises(InputError, match=r"Mach 0\.9[0-9]* .*strip_mach") as exc:
        m.state_matrix(np.array([100.0, 0.95 * a]))
    assert "\n" not in str(exc.value)
    for run in (lambda: analyse(m, speeds=np.arange(100.0, 320.0, 10.0)),
                lambda: pk_sweep(m, np.arange(100.0, 320.0, 10.0))):
        with pytest.raises(InputError, match=r"V = 310 m/s is Mach 0\.937") as exc:
            run()                                    # before any work: the top speed named
        assert "\n" not in str(exc.value)
    with pytest.raises(InputError, match="speed of sound"):
        wing_aero(pg_wing("speed"), RHO, np.array([100.0]))   # matched needs a


@pytest.mark.parametrize("kw, message", [
    (dict(compressibility="pg"), "compressibility = 'pg' is invalid"),
    (dict(compressibility="prandtl-glauert", strip_mach=0.95),
     r"strip_mach = 0\.95 is outside the valid range \[0, 0\.9\]"),
    (dict(strip_mach="matched"), "strip_mach = 'matched' is invalid"),
])
def test_bad_settings_are_one_line_errors(kw, message):
    with pytest.raises(InputError, match=message) as exc:
        Wing(**WING, **kw)
    assert "\n" not in str(exc.value)


def test_model_file_round_trip():
    model = wingtip_propeller_wing()
    m = model.with_(wing=dataclasses.replace(model.wing, compressibility="prandtl-glauert",
                                             strip_mach=0.55))
    text = io.dumps(m)
    assert 'compressibility = "prandtl-glauert"' in text and "strip_mach = 0.55" in text
    back = io.loads(text)
    assert back.wing.compressibility == "prandtl-glauert" and back.wing.strip_mach == 0.55
    V = np.array([100.0, 250.0])
    np.testing.assert_array_equal(back.state_matrix(V), m.state_matrix(V))


def test_wingtip_whirl_flutter_moves_towards_the_dlm_at_the_same_mach():
    """The 6.5 Hz whirl flutter of the wingtip model (p-k): strips 292.1 m/s, the doublet
    lattice at Mach 0.6 211.9 m/s (docs/validation.md); the Prandtl–Glauert strips at Mach 0.6
    lower it to the 2π/0.8 strips' onset (255.2 m/s computed) — towards the DLM, not to it:
    the panels' hump is three-dimensional (the strips cannot reproduce it)."""
    model = wingtip_propeller_wing()
    speeds = np.arange(200.0, 311.0, 10.0)
    m_pg = model.with_(wing=dataclasses.replace(model.wing, compressibility="prandtl-glauert",
                                                strip_mach=0.6))
    m_slope = model.with_(wing=dataclasses.replace(model.wing, lift_slope=2 * np.pi / 0.8))

    def whirl(m):
        return [f for f in pk_sweep(m, speeds, n_modes=4).flutter
                if f.event == "onset" and 5.5 < f.frequency_hz < 7.5][0]

    inc, comp, slope = whirl(model), whirl(m_pg), whirl(m_slope)
    assert abs(comp.V - slope.V) <= 0.02
    assert 0.10 < 1 - comp.V / inc.V < 0.15          # computed: 292.08 -> 255.17 (-12.6 %)
    # the default analysis (finite-state strips) sees the same move
    a = analyse(m_pg, speeds=speeds)
    fs = [e for e in a.events if e.event == "onset" and e.kind == "flutter"
          and 5.5 < e.frequency_hz < 7.5][0]
    assert abs(fs.V / comp.V - 1) < 0.02


def test_against_the_doublet_lattice_at_the_same_mach():
    """The DLM (default 8 × 29 panels) at the fixed Mach 0.6 against the strips at the same
    Mach: the Prandtl–Glauert strips close part of the gap, not all (onsets measured here;
    benchmarks/dlm_whirl_compressibility.py: DLM 211.89, Prandtl–Glauert strips 255.17,
    incompressible strips 292.08 m/s).  (On the coarse 4 × 12 panels the fixed-Mach-0.6 hump
    stays below zero: the panels' hump is sensitive to the mesh, the strips have none.)"""
    pytest.importorskip("panelaero")
    model = wingtip_propeller_wing()
    speeds = np.arange(190.0, 301.0, 10.0)

    def whirl(m):
        fl = [f for f in pk_sweep(m, speeds, n_modes=4).flutter
              if f.event == "onset" and 5.5 < f.frequency_hz < 7.5]
        return fl[0].V

    dlm = whirl(model.with_(wing=dataclasses.replace(
        model.wing, aero="dlm", dlm_mach=0.6)))
    inc = whirl(model)
    comp = whirl(model.with_(wing=dataclasses.replace(
        model.wing, compressibility="prandtl-glauert", strip_mach=0.6)))
    assert dlm < comp < inc
    # the gap to the panels shrinks by a third to a half, not to nothing
    assert 0.3 < (inc - comp) / (inc - dlm) < 0.6


@pytest.mark.parametrize("mach", ["speed", 0.5])
def test_exact_parameter_derivatives_carry_the_factor(mach):
    """∂/∂C_lα of the wing's own slope is 1/β times the generated ∂/∂Cla (and the section
    parameters are differentiated at C_lα/β): against central differences of the model."""
    from helpers.derivative_checks import assert_matches_central_differences
    from propwhirl.model import derivatives as D

    model = wingtip_propeller_wing()
    m = model.with_(wing=dataclasses.replace(model.wing, compressibility="prandtl-glauert",
                                             strip_mach=mach))
    V = np.array([60.0, 230.0])
    pars = {p.path: p for p in D.parameters(m)}
    chosen = [pars[k] for k in ("wing.lift_slope[3]", "wing.lift_slope[25]", "wing.root_chord",
                                "wing.tip_chord", "wing.chord[12]")]
    chosen += [p for p in pars.values() if p.path.startswith("wing.elastic_axis")][:2]
    chosen += [p for p in pars.values() if p.path.startswith("wing.aerodynamic_centre")][:2]
    derivs = D.second_order_derivatives(m, V, chosen)
    for par in chosen:
        assert_matches_central_differences(m, par, derivs[par.path], V)
