"""Houbolt–Reed propeller derivatives (propwhirl.model.propellers.propeller_aero, thesis chapter 4)."""
from __future__ import annotations

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import assume, given, settings as hsettings, strategies as st
from scipy import integrate
from scipy.special import hankel2, jv, yv

from helpers.work import count_calls, total
from propwhirl.model.propellers import propeller_aero as aero
from propwhirl.model.propellers.propeller_aero import (AeroSettings, DERIVATIVE_NAMES, Distribution, PropellerGeometry,
                            advance_ratio_from_blade_angle, constant_speed, derivatives,
                            theodorsen, windmilling)
from propwhirl.app.cli import main
from propwhirl.validate import InputError

GEO = PropellerGeometry(n_blades=4, radius=1.2, hub_ratio=0.2, chord=0.15)
TAB = PropellerGeometry(
    n_blades=3, radius=0.762, hub_ratio=0.164,
    chord=Distribution.tabulated([0.1, 0.3, 0.6, 1.0], [0.08, 0.12, 0.10, 0.05], "chord"),
    lift_slope=Distribution.tabulated([0.0, 0.5, 1.0], [5.8, 6.1, 5.5], "lift_slope"))


def _stack(d: aero.PropellerDerivatives) -> np.ndarray:
    return np.array([getattr(d, n) for n in DERIVATIVE_NAMES])


# ----------------------------------------------------------------------------- Theodorsen
def test_theodorsen_against_bessel_form():
    """C = (J1 − iY1)/((J1 + Y0) − i(Y1 − J0)), an evaluation independent of hankel2e."""
    k = np.logspace(-7, 3.9, 400)
    ref = (jv(1, k) - 1j * yv(1, k)) / ((jv(1, k) + yv(0, k)) - 1j * (yv(1, k) - jv(0, k)))
    assert np.max(np.abs(theodorsen(k) - ref)) < 1e-13


def test_theodorsen_against_mpmath_including_expansion_ranges():
    mp = pytest.importorskip("mpmath")
    for k in (1e-300, 1e-12, 0.99e-8, 1.01e-8, 1e-3, 0.1, 0.7, 3.0, 9.9e3, 1.01e4, 1e6, 1e12):
        with mp.workdps(40):
            h1, h0 = mp.hankel2(1, mp.mpf(k)), mp.hankel2(0, mp.mpf(k))
            ref = complex(h1 / (h1 + 1j * h0))
        assert abs(complex(theodorsen(k)) - ref) < 1e-13 * max(1.0, abs(ref)), k


@pytest.mark.parametrize("k, F, G", [
    (0.05, 0.9090, -0.1306), (0.1, 0.8319, -0.1723), (0.2, 0.7276, -0.1886),
    (0.5, 0.5979, -0.1507), (1.0, 0.5394, -0.1003), (10.0, 0.5006, -0.0124),
])
def test_theodorsen_tabulated_literature_values(k, F, G):
    c = complex(theodorsen(k))
    assert c.real == pytest.approx(F, abs=1e-4) and c.imag == pytest.approx(G, abs=1e-4)


def test_theodorsen_limits_exact_and_no_nan():
    c = theodorsen([0.0, np.inf, 1e-320, 1e300, 1e308])
    assert c[0] == 1.0 and c[1] == 0.5
    assert np.all(np.isfinite(c))
    assert abs(c[2] - 1) < 1e-300 and abs(c[3] - 0.5) < 1e-299
    # scipy's own hankel2 breaks down where the expansions take over
    assert not np.isfinite(hankel2(1, 1e-320))


def test_theodorsen_shape_and_bad_input():
    assert theodorsen(np.ones((2, 3))).shape == (2, 3)
    assert np.ndim(theodorsen(0.3)) == 0
    for bad in (-0.1, np.nan, [0.1, -1.0]):
        with pytest.raises(InputError, match="reduced frequency k"):
            theodorsen(bad)


@hsettings(max_examples=40, deadline=None)
@given(st.floats(1e-6, 1e5))
def test_theodorsen_range(k):
    c = complex(theodorsen(k))
    assert 0.5 < c.real < 1.0 and c.imag < 0.0


# ----------------------------------------------------------------------------- closed forms
def _closed_form_A(mu: float, eta0: float) -> tuple[float, float, float]:
    """Eq. 4.17 for constant chord: A1, A2, A3 analytically."""
    def prim(e):
        s = math.sqrt(mu * mu + e * e)
        ash = math.asinh(e / mu)
        p0 = ash
        p2 = 0.5 * (e * s - mu * mu * ash)
        p4 = e ** 3 * s / 4 - 3 * mu * mu * e * s / 8 + 3 * mu ** 4 * ash / 8
        return p0, p2, p4
    hi, lo = prim(1.0), prim(eta0)
    d = [h - l for h, l in zip(hi, lo)]
    return mu * mu * d[0], mu * d[1], d[2]


@pytest.mark.parametrize("nb", [3, 4, 6])
@pytest.mark.parametrize("V", [20.0, 80.0, 300.0])
def test_quasi_steady_derivatives_match_closed_form_eq_4_28(nb, V):
    """Wake, compressibility and aspect ratio off: eq. 4.28 with the integrals of 4.17 (× N_b/4)."""
    geo = PropellerGeometry(nb, 1.1, 0.15, 0.2)
    om = 150.0
    d = derivatives(geo, V, om, settings=AeroSettings(
        wake=False, compressibility=False, aspect_ratio_correction=False))
    mu = V / (om * geo.radius)
    A1, A2, A3 = (nb / 4 * a for a in _closed_form_A(mu, geo.hub_ratio))
    f = om * geo.c0 / V
    assert float(d.CY_psi) == pytest.approx(4 * f * A1, rel=1e-12)
    assert float(d.CY_q) == pytest.approx(-4 * f * A2, rel=1e-12)
    assert float(d.Cm_psi) == pytest.approx(2 * f * A2, rel=1e-12)
    assert float(d.Cm_q) == pytest.approx(-2 * f * A3, rel=1e-12)
    for n in ("CZ_psi", "CZ_q", "Cm_theta", "Cm_r", "J1", "J2", "J3"):
        assert float(getattr(d, n)) == 0.0
    # aspect-ratio correction alone at M = 0: the constant factor A/(A + 2) (eq. 4.22)
    d2 = derivatives(geo, V, om, settings=AeroSettings(wake=False, compressibility=False))
    A = geo.blade_aspect_ratio
    assert A == pytest.approx(geo.radius * (1 - geo.hub_ratio) / 0.2)   # eq. 4.21
    assert float(d2.CY_psi) == pytest.approx(float(d.CY_psi) * A / (A + 2), rel=1e-12)


def _quad_reference(geo: PropellerGeometry, V: float, om: float, a_sound: float,
                    wake: bool = True) -> dict[str, float]:
    """Eq. 4.42 with the 4.18–4.24 factors, integrated by adaptive scipy quad."""
    mu = V / (om * geo.radius)
    M = V / a_sound
    A = geo.blade_aspect_ratio
    mr2_max = 0.75

    def kernel(eta, q, part):
        c = float(geo.chord(eta))
        a = 2 * math.pi if geo.lift_slope is None else float(geo.lift_slope(eta))
        mr2 = min(M * M * (1 + eta * eta / mu / mu), mr2_max)
        g = a / (2 * math.pi) * A / (2 + A * math.sqrt(1 - mr2))
        U = math.sqrt(V * V + (om * eta * geo.radius) ** 2)
        k = om * c / (2 * U)
        h1, h0 = hankel2(1, k), hankel2(0, k)
        C = h1 / (h1 + 1j * h0) if wake else 1.0 + 0j
        val = C.real if part == "F" else C.imag
        return eta ** q * c * g * val / math.sqrt(mu * mu + eta * eta)

    pts = list(geo.knots)
    if M > 0 and M * M * (1 + 1 / mu / mu) > mr2_max:
        cut = mu * math.sqrt(max(mr2_max / M / M - 1, 0.0))
        if cut > geo.hub_ratio:
            pts.append(cut)
    s = geo.n_blades / 4 / geo.c0
    out = {}
    for name, p, q, part in (("I1", 2, 0, "F"), ("I2", 1, 2, "F"), ("I3", 0, 4, "F"),
                             ("J1", 2, 0, "G"), ("J2", 1, 2, "G"), ("J3", 0, 4, "G")):
        val, _ = integrate.quad(kernel, geo.hub_ratio, 1.0, args=(q, part), points=pts or None,
                                epsabs=1e-14, epsrel=1e-12, limit=200)
        out[name] = s * mu ** p * val
    return out


@pytest.mark.parametrize("geo", [GEO, TAB], ids=["constant", "tabulated"])
@pytest.mark.parametrize("V, om", [(30.0, 200.0), (120.0, 200.0), (250.0, 420.0)])
def test_blade_integrals_match_adaptive_quadrature(geo, V, om):
    d = derivatives(geo, V, om, speed_of_sound=340.0)
    ref = _quad_reference(geo, V, om, 340.0)
    for name, val in ref.items():
        assert float(getattr(d, name)) == pytest.approx(val, rel=1e-9, abs=1e-13), name
    f = om * geo.c0 / V                                              # eq. 4.39
    assert float(d.CZ_theta) == pytest.approx(-4 * f * ref["I1"], rel=1e-9)
    assert float(d.CZ_psi) == pytest.approx(-4 * f * ref["J1"], rel=1e-9)
    assert float(d.Cm_theta) == pytest.approx(-2 * f * ref["J2"], rel=1e-9)
    assert float(d.Cm_r) == pytest.approx(-2 * f * ref["J3"], rel=1e-9)


def test_cutoff_applied_and_matches_reference():
    """Supersonic tip: M_r² is held at 1 − (2π/4π)² (eq. 4.23–4.24), no NaN, flagged."""
    V = np.array([60.0, 200.0, 320.0])
    d = derivatives(GEO, V, 200.0, speed_of_sound=340.0)
    tip_mr2 = (V / 340.0) ** 2 * (1 + 1 / d.advance_ratio ** 2)
    assert np.array_equal(d.cutoff_applied, tip_mr2 > 0.75)
    assert d.cutoff_applied.tolist() == [False, True, True]
    assert np.all(np.isfinite(_stack(d)))
    ref = _quad_reference(GEO, 320.0, 200.0, 340.0)
    assert float(d.I3[2]) == pytest.approx(ref["I3"], rel=1e-9)
    # continuous across the onset of the cut-off (the tip reaching M_r² = 0.75)
    mu = d.advance_ratio[0]
    a_onset = 60.0 / math.sqrt(0.75 / (1 + 1 / mu ** 2))
    lo = derivatives(GEO, 60.0, 200.0, speed_of_sound=a_onset * (1 + 1e-9))
    hi = derivatives(GEO, 60.0, 200.0, speed_of_sound=a_onset * (1 - 1e-9))
    assert not lo.cutoff_applied and hi.cutoff_applied
    assert np.allclose(_stack(lo), _stack(hi), rtol=1e-7, atol=0)
    # switched off: never reported
    off = derivatives(GEO, V, 200.0, settings=AeroSettings(compressibility=False))
    assert not off.cutoff_applied.any()


# ----------------------------------------------------------------------------- structure
@pytest.mark.parametrize("sets", [
    AeroSettings(), AeroSettings(wake=False), AeroSettings(cnq_sign="rodden_rose"),
    AeroSettings(method="bennett_bland"), AeroSettings(aspect_ratio_correction=False),
])
def test_symmetry_relations_4_27(sets):
    d = derivatives(TAB, np.linspace(10, 250, 7), 350.0, speed_of_sound=340.0, settings=sets)
    pairs = [("CZ_psi", "CY_theta", 1), ("CZ_r", "CY_q", 1), ("Cm_psi", "Cn_theta", -1),
             ("Cm_r", "Cn_q", -1), ("CY_psi", "CZ_theta", -1), ("CY_r", "CZ_q", -1),
             ("Cn_psi", "Cm_theta", 1), ("Cn_r", "Cm_q", 1)]
    for a, b, s in pairs:
        assert np.array_equal(getattr(d, a), s * getattr(d, b)), (a, b)


def test_signs_and_wake_effect():
    V = np.linspace(15, 200, 9)
    d = derivatives(GEO, V, 250.0, speed_of_sound=340.0)
    assert np.all(d.CZ_theta < 0) and np.all(d.Cm_q < 0) and np.all(d.Cm_psi > 0)
    assert np.all(d.CZ_psi > 0) and np.all(d.Cm_theta > 0)             # G < 0: lift lag
    q = derivatives(GEO, V, 250.0, speed_of_sound=340.0, settings=AeroSettings(wake=False))
    assert np.all(np.abs(d.CZ_theta) < np.abs(q.CZ_theta))             # 1/2 < F < 1
    assert np.all(np.abs(d.CZ_theta) > 0.5 * np.abs(q.CZ_theta))


def test_compressibility_increases_magnitudes():
    """§4.2/Fig. 4.7: a higher Mach number raises |derivatives|."""
    d = [derivatives(GEO, 60.0, 250.0, mach=m) for m in (0.0, 0.1, 0.2, 0.3)]
    cz = [abs(float(x.CZ_theta)) for x in d]
    assert cz == sorted(cz) and cz[0] < cz[-1]
    inc = derivatives(GEO, 60.0, 250.0, settings=AeroSettings(compressibility=False))
    assert float(inc.CZ_theta) == pytest.approx(float(d[0].CZ_theta), rel=1e-14)


def test_blade_count_and_reference_chord_scaling():
    base = derivatives(GEO, 80.0, 250.0, speed_of_sound=340.0)
    six = derivatives(PropellerGeometry(6, 1.2, 0.2, 0.15), 80.0, 250.0, speed_of_sound=340.0)
    assert np.allclose(_stack(six), 1.5 * _stack(base), rtol=1e-13)
    c0 = derivatives(PropellerGeometry(4, 1.2, 0.2, 0.15, reference_chord=0.6), 80.0, 250.0,
                     speed_of_sound=340.0)
    assert np.allclose(_stack(c0), _stack(base), rtol=1e-13)            # c0 cancels
    assert float(c0.I1) == pytest.approx(float(base.I1) * 0.15 / 0.6, rel=1e-13)


def test_cnq_sign_option():
    t = derivatives(GEO, 80.0, 250.0, speed_of_sound=340.0)
    r = derivatives(GEO, 80.0, 250.0, speed_of_sound=340.0,
                    settings=AeroSettings(cnq_sign="rodden_rose"))
    f = 250.0 * GEO.c0 / 80.0
    assert float(t.Cn_q) == pytest.approx(2 * f * float(t.J3), rel=1e-13)     # thesis 4.39
    assert float(r.Cn_q) == pytest.approx(-2 * f * float(t.J3), rel=1e-13)    # R&R, §4.1.6
    for n in DERIVATIVE_NAMES:
        s = -1.0 if n in ("Cn_q", "Cm_r") else 1.0
        assert float(getattr(r, n)) == s * float(getattr(t, n)), n


def test_bennett_bland_variant():
    V = np.array([20.0, 40.0, 90.0])
    bb = derivatives(GEO, V, 200.0, speed_of_sound=340.0,
                     settings=AeroSettings(method="bennett_bland"))
    qs = derivatives(GEO, V, 200.0, settings=AeroSettings(wake=False, compressibility=False))
    for n in ("CZ_theta", "Cm_psi", "Cm_q", "CY_q"):                   # eq. 4.28 at M = 0
        assert np.allclose(getattr(bb, n), getattr(qs, n), rtol=1e-14)
    mu = V / (200.0 * GEO.radius)
    k75 = GEO.c0 / (2 * GEO.radius * np.sqrt(0.75 ** 2 + mu ** 2))      # eq. 4.45
    C = theodorsen(k75)
    tan_delta = np.tan(np.arctan(-C.imag / C.real))                    # eq. 4.44
    assert np.allclose(bb.CZ_psi, bb.CY_psi * tan_delta, rtol=1e-13)   # eq. 4.43
    assert np.allclose(bb.Cm_theta, bb.Cm_psi * tan_delta, rtol=1e-13)  # eq. 4.46
    assert np.all(bb.CZ_q == 0) and np.all(bb.Cm_r == 0) and np.all(bb.Cn_q == 0)
    # the speed of sound does not enter (M = 0)
    bb2 = derivatives(GEO, V, 200.0, speed_of_sound=100.0,
                      settings=AeroSettings(method="bennett_bland"))
    assert np.array_equal(_stack(bb), _stack(bb2)) and not bb2.cutoff_applied.any()


# ----------------------------------------------------------------------------- operating points
def test_eq_9_1_advance_ratio_matches_thesis_chapter_9():
    """J = π tan(β − 3°) for β = 35°: J = 1.96 (Table 9.3); 221 m/s at 4433 RPM, R = 0.762 m."""
    mu = advance_ratio_from_blade_angle(math.radians(35.0))
    assert math.pi * mu == pytest.approx(1.96, abs=0.005)
    geo = PropellerGeometry(3, 0.762, 0.164, 0.094)
    d = windmilling(geo, 221.0, math.radians(35.0), speed_of_sound=340.0)
    assert float(d.omega) * 30 / math.pi == pytest.approx(4433, abs=1.0)
    be = advance_ratio_from_blade_angle(math.radians(35.0), rule="blade_element")
    assert be == pytest.approx(0.75 * math.tan(math.radians(38.0)), rel=1e-15)
    assert advance_ratio_from_blade_angle(math.radians(35.0), math.radians(-2.0)) == \
        pytest.approx(math.tan(math.radians(33.0)), rel=1e-15)


def test_windmilling_and_constant_speed_over_arrays():
    V = np.linspace(5.0, 300.0, 50)
    w = windmilling(TAB, V, math.radians(30.0), speed_of_sound=340.0)
    assert np.allclose(w.advance_ratio, math.tan(math.radians(27.0)), rtol=1e-14)
    assert np.all(np.diff(w.omega) > 0)                                # Ω rises with V
    c = constant_speed(TAB, V, 300.0, speed_of_sound=340.0)
    assert np.all(c.omega == 300.0)
    assert np.allclose(c.advance_ratio, V / (300.0 * TAB.radius), rtol=1e-15)
    # one vectorised call equals point-by-point calls
    for i in (0, 17, 49):
        one = constant_speed(TAB, V[i], 300.0, speed_of_sound=340.0)
        assert np.allclose(_stack(one), _stack(c)[:, i], rtol=1e-12, atol=0)
    two_d = derivatives(TAB, V.reshape(5, 10), 300.0, speed_of_sound=340.0)
    assert two_d.CZ_theta.shape == (5, 10)
    assert np.allclose(two_d.CZ_theta.ravel(), c.CZ_theta, rtol=1e-12)


def test_400_speeds_cost_the_python_work_of_4():
    """Vectorised over speeds: the derivatives at 400 speeds make exactly the Python-level calls
    of 4 speeds (counted, not timed: no loop over speeds; NumPy does the per-speed work)."""
    V = np.linspace(5.0, 320.0, 400)
    derivatives(TAB, V[::100], 300.0, speed_of_sound=340.0)              # warm up (imports)
    _, few = count_calls(derivatives, TAB, V[::100], 300.0, speed_of_sound=340.0)
    d, many = count_calls(derivatives, TAB, V, 300.0, speed_of_sound=340.0)
    assert total(many) == total(few) > 0
    assert d.cutoff_applied.any() and np.all(np.isfinite(_stack(d)))


# ----------------------------------------------------------------------------- quadrature
@pytest.mark.parametrize("geo", [PropellerGeometry(4, 1.0, 0.0, 0.1), TAB, GEO],
                         ids=["no-hub", "tabulated", "constant"])
@pytest.mark.parametrize("om", [50.0, 400.0, 1500.0])
def test_quadrature_converged_when_order_doubles(geo, om):
    """Default order vs twice the order: every output stable to 1e-8 (relative to its scale)."""
    V = np.array([3.0, 20.0, 80.0, 200.0, 320.0])                     # μ from 0.002 to 6
    n = AeroSettings().quadrature_order
    a = derivatives(geo, V, om, speed_of_sound=340.0)
    b = derivatives(geo, V, om, speed_of_sound=340.0,
                    settings=AeroSettings(quadrature_order=2 * n))
    for name in DERIVATIVE_NAMES + ("I1", "I2", "I3", "J1", "J2", "J3"):
        x, y = getattr(a, name), getattr(b, name)
        assert np.all(np.abs(x - y) <= 1e-8 * np.maximum(np.abs(y), 1e-6)), name


# ----------------------------------------------------------------------------- geometry
def test_distributions_and_aspect_ratio():
    taper = Distribution.linear(0.2, 0.1, 0.25)
    geo = PropellerGeometry(4, 2.0, 0.25, taper)
    assert float(geo.chord(0.625)) == pytest.approx(0.15)
    assert geo.blade_area() == pytest.approx(2.0 * 0.75 * 0.15)
    assert geo.blade_aspect_ratio == pytest.approx(4.0 * 0.75 ** 2 / (2.0 * 0.75 * 0.15))
    assert geo.c0 == pytest.approx(0.2 - 0.1 * 0.5 / 0.75)
    assert PropellerGeometry(4, 2.0, 0.25, taper, aspect_ratio=7.0).blade_aspect_ratio == 7.0
    fn = PropellerGeometry(4, 2.0, 0.25, lambda e: 0.25 - 0.1 * e)
    assert fn.blade_area() == pytest.approx(taper_area := 2.0 * 0.75 * (0.25 - 0.1 * 0.625))
    assert taper_area > 0
    lin = derivatives(geo, 50.0, 100.0, speed_of_sound=340.0)
    call = derivatives(PropellerGeometry(4, 2.0, 0.25, lambda e: np.interp(e, [0.25, 1], [0.2, 0.1])),
                       50.0, 100.0, speed_of_sound=340.0)
    assert np.allclose(_stack(lin), _stack(call), rtol=1e-12)


def test_houbolt_reed_source_adapter():
    prop = SimpleNamespace(n_blades=4, radius=1.2, hub_radius=0.24, blade_chord=0.15)
    src = aero.houbolt_reed_source(prop)
    V = np.array([30.0, 90.0])
    out = src(V, np.array([200.0, 250.0]), 340.0)
    ref = derivatives(GEO, V, np.array([200.0, 250.0]), speed_of_sound=340.0)
    assert set(out) == set(DERIVATIVE_NAMES)
    for n in DERIVATIVE_NAMES:
        assert np.allclose(out[n], getattr(ref, n), rtol=1e-14)


# ----------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("kwargs, match", [
    (dict(n_blades=2), r"n_blades = 2 .*\[3, 20\]"),
    (dict(n_blades=3.0), r"n_blades = 3.0"),
    (dict(radius=0.0), r"radius = 0.0 m .*\[0.01, 20\] m"),
    (dict(radius=-1.0), r"radius = -1.0 m"),
    (dict(radius=float("nan")), r"radius = nan m .*finite"),
    (dict(hub_ratio=1.0), r"hub_ratio = 1.0 .*\[0, 1\)"),
    (dict(hub_ratio=-0.1), r"hub_ratio = -0.1"),
    (dict(hub_ratio=float("inf")), r"hub_ratio = inf .*finite"),
    (dict(chord=-0.1), r"chord = -0.1 m"),
    (dict(chord=lambda e: 0.1 - 0.2 * e), r"chord\(eta = .*\) = .*\[1e-3, 5\] m"),
    (dict(aspect_ratio=0.0), r"aspect_ratio = 0.0"),
    (dict(reference_chord=float("inf")), r"reference_chord = inf"),
    (dict(hub_ratio=0.05, chord=Distribution.tabulated([0.1, 1.0], [0.1, 0.1], "chord")),
     r"chord table covers eta in \[0.1, 1.0\].*\[0.05, 1.0\]"),
])
def test_bad_geometry(kwargs, match):
    base = dict(n_blades=4, radius=1.0, hub_ratio=0.2, chord=0.1)
    with pytest.raises(InputError, match=match):
        PropellerGeometry(**{**base, **kwargs})


def test_bad_distributions():
    with pytest.raises(InputError, match=r"chord eta is invalid: must be strictly increasing"):
        Distribution.tabulated([0.0, 0.5, 0.4, 1.0], [1, 1, 1, 1], "chord")
    with pytest.raises(InputError, match=r"lift_slope values = -6.0"):
        Distribution.tabulated([0.0, 1.0], [6.0, -6.0], "lift_slope")
    with pytest.raises(InputError, match=r"one value per station"):
        Distribution.tabulated([0.0, 0.5, 1.0], [6.0, 6.0], "lift_slope")
    with pytest.raises(InputError, match=r"chord eta = nan"):
        Distribution.tabulated([0.0, float("nan")], [0.1, 0.1], "chord")


@pytest.mark.parametrize("call, match", [
    (lambda: derivatives(GEO, 0.0, 100.0, 340.0), r"airspeed = 0.0 m/s .*> 0"),
    (lambda: derivatives(GEO, [10.0, -5.0], 100.0, 340.0), r"airspeed = -5.0 m/s"),
    (lambda: derivatives(GEO, float("nan"), 100.0, 340.0), r"airspeed = nan m/s .*finite"),
    (lambda: derivatives(GEO, 10.0, 0.0, 340.0), r"omega = 0.0 rad/s .*> 0"),
    (lambda: derivatives(GEO, 10.0, float("inf"), 340.0), r"omega = inf rad/s"),
    (lambda: derivatives(GEO, 10.0, 100.0, -340.0), r"speed_of_sound = -340.0 m/s"),
    (lambda: derivatives(GEO, 10.0, 100.0, mach=-0.1), r"mach = -0.1"),
    (lambda: derivatives(GEO, 10.0, 100.0), r"speed_of_sound \(or mach\) is missing"),
    (lambda: derivatives(GEO, 10.0, 100.0, 340.0, 0.1), r"either speed_of_sound or mach"),
    (lambda: constant_speed(GEO, 10.0, [100.0, 200.0], 340.0), r"omega has shape"),
    (lambda: derivatives(GEO, [10.0, 20.0], [1.0, 2.0, 3.0], 340.0), r"must broadcast"),
    (lambda: derivatives(GEO, [10.0, 20.0], 100.0, mach=[0.1, 0.2, 0.3]), r"mach shape"),
    (lambda: windmilling(GEO, 10.0, math.radians(2.0), 340.0), r"blade_angle = 2 deg .*φ = -1 deg"),
    (lambda: advance_ratio_from_blade_angle(0.5, rule="x"), r"rule = 'x'"),
    (lambda: AeroSettings(cnq_sign="plus"), r"cnq_sign = 'plus'"),
    (lambda: AeroSettings(method="ribner"), r"method = 'ribner'"),
    (lambda: AeroSettings(quadrature_order=1), r"quadrature_order = 1"),
    (lambda: AeroSettings(cutoff_lift_slope=6.0), r"cutoff_lift_slope = 6.0"),
    (lambda: AeroSettings(wake="yes"), r"wake = 'yes'"),
])
def test_bad_operating_point_and_settings(call, match):
    with pytest.raises(InputError, match=match):
        call()


# ----------------------------------------------------------------------------- property test
@hsettings(max_examples=30, deadline=None)
@given(nb=st.integers(3, 8), R=st.floats(0.2, 3.0), eta0=st.floats(0.0, 0.5),
       c_ratio=st.floats(0.03, 0.4), V=st.floats(1.0, 400.0), tip_speed=st.floats(20.0, 400.0),
       a=st.floats(250.0, 360.0))
def test_outputs_finite_and_consistent(nb, R, eta0, c_ratio, V, tip_speed, a):
    # only discs the blades do not overfill (solidity N_b c (1 - eta0) / (pi R) <= 1: beyond it
    # the model refuses the geometry, tested in test_propeller_aero_validity.py)
    assume(nb * c_ratio * (1.0 - eta0) / np.pi <= 1.0)
    geo = PropellerGeometry(nb, R, eta0, c_ratio * R)
    d = derivatives(geo, V, tip_speed / R, speed_of_sound=a)
    vals = _stack(d)
    assert np.all(np.isfinite(vals))
    assert d.CZ_theta < 0 and d.Cm_q < 0 and d.Cm_psi > 0 and d.CZ_psi > 0 and d.Cm_theta > 0
    assert d.CY_psi == -d.CZ_theta and d.Cn_r == d.Cm_q


# ----------------------------------------------------------------------------- CLI
CLI_BASE = ["derivatives", "--blades", "4", "--radius", "1.2", "--hub-ratio", "0.2",
            "--chord", "0.15", "--speed", "30", "90", "--rpm", "2000", "--speed-of-sound", "340"]


def test_cli_table(capsys):
    assert main(CLI_BASE) == 0
    out = capsys.readouterr().out
    for n in DERIVATIVE_NAMES:
        assert n in out
    ref = derivatives(GEO, np.array([30.0, 90.0]), 2000 * math.pi / 30, speed_of_sound=340.0)
    line = next(ln for ln in out.splitlines() if ln.startswith("CZ_theta"))
    assert [float(x) for x in line.split()[1:]] == pytest.approx(ref.CZ_theta, rel=1e-5)


def test_cli_json_and_windmilling(capsys):
    assert main(CLI_BASE + ["--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    ref = derivatives(GEO, np.array([30.0, 90.0]), 2000 * math.pi / 30, speed_of_sound=340.0)
    assert len(data["points"]) == 2
    for n in DERIVATIVE_NAMES:
        assert [p[n] for p in data["points"]] == pytest.approx(getattr(ref, n), rel=1e-14)
    wm = ["derivatives", "--blades", "3", "--radius", "0.762", "--chord-table", "0.1", "0.08",
          "1.0", "0.05", "--hub-ratio", "0.164", "--speed", "221", "--blade-angle", "35",
          "--no-wake", "--cnq-sign", "rodden_rose", "--json"]
    assert main(wm) == 0
    p = json.loads(capsys.readouterr().out)["points"][0]
    assert p["omega"] * 30 / math.pi == pytest.approx(4433, abs=1)
    assert p["CZ_psi"] == 0.0
    assert main(CLI_BASE + ["--method", "bennett_bland", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["points"][0]["CZ_q"] == 0.0


@pytest.mark.parametrize("extra, msg", [
    (["--blades", "2"], "n_blades = 2"),
    (["--hub-ratio", "1.5"], "hub_ratio = 1.5"),
    (["--speed", "-3"], "airspeed = -3.0"),
    (["--chord-table", "0", "0.1", "1"], "--chord-table"),
    (["--speed-of-sound", "0"], "speed_of_sound = 0.0"),
])
def test_cli_bad_input(capsys, extra, msg):
    assert main(CLI_BASE + extra) == 2
    assert msg in capsys.readouterr().err


def test_source_gives_the_derivatives_without_the_result_object(monkeypatch):
    """A HouboltReedSource (what a model's matrices ask at every evaluation) returns exactly
    the derivatives of derivatives(), bit for bit and in V's shape, and builds no
    PropellerDerivatives (work counted: the sixteen arrays only)."""
    src = aero.HouboltReedSource(TAB, AeroSettings())
    V = np.linspace(5.0, 320.0, 12).reshape(3, 4)
    ref = derivatives(TAB, V, 300.0, speed_of_sound=340.0)

    def refused(*args, **kwargs):
        raise AssertionError("a PropellerDerivatives was built")

    monkeypatch.setattr(aero, "PropellerDerivatives", refused)
    d, calls = count_calls(src, V, np.full(V.shape, 300.0), 340.0)
    assert list(d) == list(DERIVATIVE_NAMES)
    for name in DERIVATIVE_NAMES:
        assert d[name].shape == V.shape
        assert d[name].tobytes() == getattr(ref, name).tobytes(), name
    assert sum(n for (f, fn), n in calls.items() if fn == "_check_finite") == 1


def test_non_finite_derivative_still_named():
    """The one-test-of-all fast path of _check_finite leaves the message naming the first
    non-finite derivative and its operating point."""
    d = {n: np.ones(3) for n in DERIVATIVE_NAMES}
    d["Cm_q"] = np.array([1.0, np.inf, 1.0])
    with pytest.raises(InputError, match=r"Cm_q is not finite at V = 2 m/s"):
        aero._check_finite(GEO, d, np.array([1.0, 2.0, 3.0]), np.full(3, 100.0),
                           np.array([0.1, 0.2, 0.3]))
