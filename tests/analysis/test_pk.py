"""The p-k method with the exact Theodorsen function (propwhirl.analysis.pk) against an
independent solution of the classical flutter determinant, the analytic divergence speed, and
the finite-state (Jones) eigenvalue analysis."""
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import hankel1, hankel2

from propwhirl.analysis import analyse
from propwhirl.analysis.pk import pk_flutter, pk_sweep
from propwhirl.model.systems import FlightCondition, TypicalSection
from propwhirl.validate import InputError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

RHO = 1.225
SPEEDS = np.linspace(5.0, 200.0, 40)


def section(**kw):
    """Hodges & Pierce's typical section (Introduction to Structural Dynamics and
    Aeroelasticity, the example of its flutter chapter): μ = 20, a = −1/5, x_α = 1/10,
    r² = 6/25, σ = ω_h/ω_α = 2/5."""
    b = kw.pop("b", 1.0)
    mu = kw.pop("mu", 20.0)
    base = dict(b=b, a=-0.2, x_alpha=0.1, r_alpha=np.sqrt(6 / 25), m=mu * np.pi * RHO * b**2,
                omega_h=0.4 * 50.0, omega_alpha=50.0, flight=FlightCondition(RHO))
    base.update(kw)
    return TypicalSection(**base)


def C_exact(k):
    """Theodorsen's C(k) = H1⁽²⁾/(H1⁽²⁾ + i H0⁽²⁾), from scipy's Hankel functions (not the
    package's theodorsen())."""
    h1, h0 = hankel2(1, k), hankel2(0, k)
    return h1 / (h1 + 1j * h0)


def determinant_flutter(sec):
    """Theodorsen's classical solution: per unit (πρb³ω², πρb⁴ω²) the harmonic equations of
    motion are D(k) + X diag(μσ², μr²) with X = (ω_α/ω)²(1 + ig); det = 0 is a quadratic in X
    for each k, and flutter is where a root X is real (g = 0).  Returns (V [m/s], ω [rad/s])
    of the lowest flutter speed.  Flat plate (C_lα = 2π, a_c = −1/2) only."""
    mu = sec.m / (np.pi * RHO * sec.b**2)
    a, xa, r2 = sec.a, sec.x_alpha, sec.r_alpha**2
    s2 = (sec.omega_h / sec.omega_alpha) ** 2

    def X_roots(k):
        C = C_exact(k)
        # L/(πρb³ω²) and M/(πρb⁴ω²) per [h/b, α] (L up, h down, M nose-up, ω² factored
        # out); the circulatory moment is b(a + 1/2) times the circulatory lift
        w = 2 * C / k * np.array([1j, 1 / k + 1j * (0.5 - a)])
        L = np.array([-1.0, 1j / k + a]) + w
        M = np.array([-a, -1j * (0.5 - a) / k + (1 / 8 + a**2)]) + (a + 0.5) * w
        D = np.array([[-mu, -mu * xa], [-mu * xa, -mu * r2]]) + np.array([L, -M])
        # det(D + X diag(p1, p2)) = p1 p2 X² + (p1 D22 + p2 D11) X + det D
        p1, p2 = mu * s2, mu * r2
        return np.roots([p1 * p2, p1 * D[1, 1] + p2 * D[0, 0], np.linalg.det(D)])

    found = []
    ks = np.geomspace(3.0, 0.02, 600)
    for branch in range(2):
        def im(k):
            X = X_roots(k)
            return X[np.argsort(X.real)][branch].imag
        vals = np.array([im(k) for k in ks])
        for i in np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:])):
            kf = brentq(im, ks[i + 1], ks[i], xtol=1e-14)
            X = X_roots(kf)[np.argsort(X_roots(kf).real)][branch].real
            if X > 0:
                omega = sec.omega_alpha / np.sqrt(X)
                found.append((omega * sec.b / kf, omega))
    return min(found)


@pytest.mark.parametrize("kw", [{}, {"mu": 10.0}, {"a": -0.4, "x_alpha": 0.2}, {"b": 0.3}])
def test_pk_flutter_equals_the_exact_flutter_determinant(kw):
    sec = section(**kw)
    Vd, wd = determinant_flutter(sec)
    f = [e for e in pk_flutter(sec, SPEEDS * 1.5) if e.kind == "flutter"][0]
    assert f.event == "onset"
    # the p-k root is exact at Re p = 0; the flutter speed is converged to 0.01 m/s
    assert f.V == pytest.approx(Vd, abs=0.02)
    # ω and k are evaluated at that speed: |dω/dV| · 0.01 m/s ≈ 2e-5 ω
    assert f.frequency == pytest.approx(wd, rel=1e-4)
    assert f.k == pytest.approx(wd * sec.b / Vd, rel=3e-4)


def test_hodges_pierce_example_flutter_speed():
    """Independent determinant and p-k: U_F/(bω_α) = 2.18, ω_F/ω_α = 0.65 for this section."""
    sec = section()
    f = pk_sweep(sec, SPEEDS).critical
    assert f.kind == "flutter"
    assert f.V / (sec.b * sec.omega_alpha) == pytest.approx(2.184, abs=0.002)
    assert f.frequency / sec.omega_alpha == pytest.approx(0.649, abs=0.002)


def test_divergence_is_the_analytic_divergence_speed():
    """A root turns real and crosses zero at q_D = K_α/(2π b² (a + 1/2)) (C(0) = 1):
    U_D = b ω_α sqrt(μ r² / (2 (a + 1/2)))."""
    sec = section()
    div = [e for e in pk_flutter(sec, SPEEDS) if e.kind == "divergence"]
    assert len(div) == 1 and div[0].frequency == 0.0
    UD = sec.b * sec.omega_alpha * np.sqrt(20.0 * 0.24 / (2 * (sec.a + 0.5)))
    assert div[0].V == pytest.approx(UD, abs=0.02)


@pytest.mark.parametrize("aero_model", ["leishman-nguyen", "wagner"])
def test_finite_state_within_one_percent_of_exact(aero_model):
    sec = section(aero_model=aero_model)
    exact = [e for e in pk_flutter(sec, SPEEDS) if e.kind == "flutter"][0]
    fs = analyse(sec, speeds=SPEEDS).critical
    assert fs.kind == "flutter"
    assert abs(fs.V / exact.V - 1) < 0.01
    assert abs(2 * np.pi * fs.frequency_hz / exact.frequency - 1) < 0.01


def test_bad_input():
    with pytest.raises(InputError, match="model"):
        pk_flutter(section().without_aerodynamics(), SPEEDS)
    with pytest.raises(InputError, match="speeds"):
        pk_flutter(section(), [10.0, 5.0])


def test_analyse_method_pk_gives_the_pk_events_on_the_tracked_modes():
    sec = section()
    fs = analyse(sec, speeds=SPEEDS)
    pk = analyse(sec, speeds=SPEEDS, method="pk")
    exact = pk_sweep(sec, SPEEDS)
    assert [(e.kind, e.event) for e in pk.events] == [("flutter", "onset"), ("divergence", "onset")]
    assert pk.critical.V == exact.critical.V
    assert pk.critical.frequency_hz == exact.critical.frequency_hz
    # the same mode (name) flutters in both, the p-k speed 0.6 % above the finite-state one
    assert pk.critical.label == fs.critical.label
    assert pk.critical.V != fs.critical.V
    assert pk.events[1].V == pytest.approx(np.sqrt(8.0) * sec.b * sec.omega_alpha, abs=0.02)


def test_method_pk_only_for_typical_sections():
    from propwhirl.cases.ch09_baseline import isolated_baseline_propeller

    with pytest.raises(InputError, match="p-k"):
        analyse(isolated_baseline_propeller(), speeds=[100.0, 200.0], method="pk")
    with pytest.raises(InputError, match="'pk'"):
        analyse(section(), speeds=SPEEDS, method="p-k")


def test_a_mode_whose_k_iteration_fails_is_said_not_dropped(monkeypatch):
    """If the k iteration does not converge at some speed, the sweep stops following the mode
    there, reports no crossing from its NaN roots, and the analysis says so in its warnings."""
    import propwhirl.analysis.pk as PK

    sec = section()
    real = PK.pk_root
    stop = SPEEDS[3]

    def failing(model, V, p0, **kw):
        if V >= stop:
            raise RuntimeError("no convergence (test)")
        return real(model, V, p0, **kw)

    real_roots = PK.pk_roots

    def failing_roots(model, V, p0, system, **kw):   # the sweep's batched k iterations
        if V >= stop:
            n = np.size(p0)
            return np.full(n, complex(np.nan, np.nan)), np.full(n, np.nan)
        return real_roots(model, V, p0, system, **kw)

    monkeypatch.setattr(PK, "pk_root", failing)
    monkeypatch.setattr(PK, "pk_roots", failing_roots)
    r = PK.pk_sweep(sec, SPEEDS)
    assert len(r.lost) == len(r.labels) and all(V == stop for _, V in r.lost)
    assert np.all(np.isnan(r.roots[3:])) and np.all(np.isfinite(r.roots[:3]))
    assert all(e.V < stop for e in r.flutter)
    a = analyse(sec, speeds=SPEEDS, method="pk")
    notes = [w for w in a.warnings if "did not converge" in w]
    assert len(notes) == len(r.labels)


def test_every_in_vacuo_mode_starts_from_its_own_root():
    """Two close modes (the wingtip wing's 16.68 and 18.06 Hz) both took the finite-state root
    nearest each, 17.96 Hz, so the mode that flutters was never followed: the p-k reported
    divergence alone where the default and NASTRAN-95 have flutter at 160.4 m/s (DLM) and the
    strips at 150 m/s.  Each in-vacuo mode now has a root of its own."""
    from propwhirl.analysis.pk import _start_roots
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

    model = wingtip_propeller_wing().with_(propellers=())
    start, labels = _start_roots(model, 100.0, None)
    assert len(start) == len(labels) == 75
    assert len(np.unique(np.round(start, 9))) == len(start)


def test_the_pk_follows_the_mode_that_flutters_between_two_close_modes():
    from propwhirl.analysis import analyse
    from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing

    model = wingtip_propeller_wing().with_(propellers=())
    V = np.linspace(100.0, 200.0, 11)
    pk, fs = analyse(model, V, method="pk"), analyse(model, V)
    flutter = [e for e in pk.events if e.kind == "flutter" and e.event == "onset"]
    ref = [e for e in fs.events if e.kind == "flutter" and e.event == "onset"]
    assert len(flutter) == len(ref) == 1
    # exact Theodorsen (p-k) against the finite-state lags (default): 0.7 % apart here
    assert flutter[0].V == pytest.approx(ref[0].V, rel=0.01)
    assert flutter[0].frequency_hz == pytest.approx(ref[0].frequency_hz, rel=0.03)


def test_the_pk_follows_each_of_many_near_identical_propellers_whirl_modes():
    """x57_like: seven propellers, six near-identical (whirl modes ~1e-3 apart). The p-k
    followed the lowest six modes only, and those of a cluster collapsed onto one root speed
    by speed: no instability, where the default has whirl flutter from 80.0 m/s. It now
    follows the modes up to the reduced models' cut-off, each on a root of its own."""
    from propwhirl import io
    from propwhirl.analysis import analyse
    from propwhirl.analysis.pk import followed_modes, pk_sweep

    model = io.load_model(EXAMPLES / "x57_like.toml")
    V = np.arange(60.0, 100.1, 5.0)
    assert followed_modes(model, V) == 18
    r = pk_sweep(model, V)
    for i in range(V.size):                      # no two modes on one root at any speed
        p = r.roots[i][np.isfinite(r.roots[i])]
        gap = np.abs(p[:, None] - p[None, :]) + np.eye(p.size) * 1e9
        assert gap.min() > 1e-7 * np.abs(p).min()
    pk, fs = analyse(model, V, method="pk"), analyse(model, V)
    assert pk.critical is not None and pk.critical.kind == "flutter"
    # the whirl flutter is the propellers' (quasi-steady Houbolt-Reed loads): the exact C(k)
    # and the finite-state lags differ little there (measured 2.5e-5 relative)
    assert pk.critical.V == pytest.approx(fs.critical.V, rel=1e-4)


def test_the_pk_critical_of_near_identical_propellers_does_not_depend_on_the_grid():
    """x57_like on a 2.5 m/s grid: Brent's method in each bracket continued every speed's
    root from the bracket's left root, 2.5 m/s away; in the cluster (roots ~1e-3 of |p|
    apart) the modes of four brackets all took one root inside them and converged onto one
    crossing, 80.66 m/s — the critical 79.99 m/s (the default's 80.00; on the example's own
    10 m/s grid found) was missing. From the root interpolated between the bracket's ends
    each keeps its own."""
    from propwhirl import io
    from propwhirl.analysis import analyse
    from propwhirl.analysis.pk import pk_sweep

    model = io.load_model(EXAMPLES / "x57_like.toml")
    V = np.arange(1.0, 120.1, 2.5)
    onsets = [e for e in pk_sweep(model, V).flutter if e.event == "onset"]
    fs = analyse(model, V)
    assert onsets[0].V == pytest.approx(fs.critical.V, rel=1e-4)   # measured 3e-5
    assert len(onsets) >= 5                        # the cluster's own crossings (measured 5)


def test_the_pk_finds_the_same_cluster_onsets_on_every_grid():
    """x57_like's six near-identical propellers (roots ~1e-3 of |p| apart, moving ~9 % of |p|
    per 10 m/s): with the nearest-root rule the p-k's onsets of the cluster depended on the
    grid (1-250 m/s every 10 / 5 / 2.5 m/s: 5 / 3 / 5 of the six propellers' and propeller
    7's on two of the three). A tight cluster is now followed by its modes' shapes in steps
    that move its roots by no more than pk.TIGHT of |p|: the same onsets on every grid, as
    many as the default's, each within 0.1 m/s of the default's of the same name."""
    from propwhirl import io
    from propwhirl.analysis import analyse
    from propwhirl.analysis.pk import pk_sweep

    model = io.load_model(EXAMPLES / "x57_like.toml")
    fs = [e for e in analyse(model, np.arange(60.0, 100.1, 2.5)).events
          if e.kind == "flutter" and e.event == "onset"]
    found = []
    for step in (10.0, 5.0, 2.5):
        onsets = [e for e in pk_sweep(model, np.arange(60.0, 100.1, step)).flutter
                  if e.kind == "flutter" and e.event == "onset"]
        found.append(np.array([e.V for e in onsets]))
    assert all(f.size == len(fs) == 6 for f in found), found
    for f in found[1:]:
        assert f == pytest.approx(found[0], abs=0.02)
    pk = analyse(model, np.arange(60.0, 100.1, 10.0), method="pk")
    default = {e.label: e.V for e in fs}
    for e in (e for e in pk.events if e.kind == "flutter" and e.event == "onset"):
        assert e.V == pytest.approx(default[e.label], abs=0.2)


def test_the_pk_names_each_whirl_flutter_of_near_identical_propellers_as_the_default():
    """x57_like (issue 34 item 4): never two different events under one name, each named as
    the default names it. The p-k named its events from the swept root before the crossing
    (in a cluster nearer another mode's root at the crossing: the critical was 'forward whirl,
    propeller 7' at 7.26 Hz, where the default's is '(1 of 6, collective)' at 7.02 Hz, and
    two events were '(3 of 6)'), two modes of the cluster met on one root 8e-7 apart (one
    flutter unfollowed), and a mode whose root hopped onto another's between two speeds had
    its 'crossing' at the hop (propeller 7's, Re p = -0.025 there)."""
    from propwhirl import io

    model = io.load_model(EXAMPLES / "x57_like.toml")
    V = np.linspace(10, 120, 23)
    pk, fs = analyse(model, V, method="pk"), analyse(model, V)
    onsets = [e for e in pk.events if e.kind == "flutter" and e.event == "onset"]
    ref = [e for e in fs.events if e.kind == "flutter" and e.event == "onset"]
    assert len(ref) == 6
    assert len({e.label for e in onsets}) == len(onsets)          # one event, one name
    assert sorted(e.label for e in onsets) == sorted(e.label for e in ref)
    by_label = {e.label: e for e in onsets}
    for e in ref:
        assert by_label[e.label].frequency_hz == pytest.approx(e.frequency_hz, rel=0.01)
        assert by_label[e.label].V == pytest.approx(e.V, rel=5e-3)
    assert pk.critical.label == fs.critical.label


def test_one_to_one_gives_each_event_of_a_cluster_its_own_mode():
    """Two onsets close in speed that tracked_mode gives one mode are assigned one to one by
    their shapes' MAC; an event far in speed, or of another direction, keeps its mode."""
    from types import SimpleNamespace

    from propwhirl.analysis.pk import one_to_one

    shapes = np.array([[1.0, 0.1j, 0.0], [0.1, 1.0, 0.0], [0.0, 0.0, 1.0]])  # mode per column
    X = np.zeros((2, 6, 3), complex)
    X[:, :3] = shapes
    sw = SimpleNamespace(V=np.array([80.0, 85.0]), physical=np.ones((2, 3), bool),
                         displacement=np.arange(6) < 3, eigenvectors=X)
    x0, x1 = shapes[:, 0] * 1j, shapes[:, 1] * (1 - 2j)
    on = ("flutter", "onset")
    assert one_to_one(sw, [0, 0], [x0, x1], [80.0, 80.5], [on, on]) == [0, 1]
    assert one_to_one(sw, [0, 0], [x1, x0], [80.0, 80.5], [on, on]) == [1, 0]
    assert one_to_one(sw, [0, 0], [x0, x1], [80.0, 120.0], [on, on]) == [0, 0]
    assert one_to_one(sw, [0, 0], [x0, x1], [80.0, 80.5],
                      [on, ("flutter", "recovery")]) == [0, 0]
    # a mode another event of the window holds is not given again
    assert one_to_one(sw, [0, 0, 1], [x0, x1, x1], [80.0, 80.5, 80.2], [on, on, on]) == [0, 2, 1]


def _hopping_roots(monkeypatch):
    """pk_crossings.pk_root replaced by two branches that never cross zero near 80 m/s (Re p
    −0.0144 and +0.0034 1/s, slope 0.015 per m/s) with the root jumping from one to the other
    at 80.3311 m/s, as x57_like's neighbouring propellers' roots did on panels."""
    from propwhirl.analysis import pk_crossings as pk

    def root(model, V, p0, **kw):
        if V < 80.3311:
            return complex(-0.0144 + 0.015 * (V - 80.3311), 44.095), 0.2
        return complex(0.0034 + 0.015 * (V - 80.3311), 44.146), 0.2

    monkeypatch.setattr(pk, "pk_root", root)
    return pk


def test_a_secant_converging_on_a_hop_is_no_crossing(monkeypatch):
    pk = _hopping_roots(monkeypatch)
    for V0 in (80.1, 80.4, 80.7):          # the old secant converged on the jump from these
        assert pk.full_crossing(None, V0, 44.1j, 0.015, lo=78.0, hi=82.0) is None


def test_brents_method_converging_on_a_hop_is_no_crossing(monkeypatch):
    """The bracket around 80.33 m/s changes sign only by the jump: Brent's method converges
    onto it (Re p = +0.0034 there); that is no crossing of the p-k, so none is reported."""
    pk = _hopping_roots(monkeypatch)
    monkeypatch.setattr(pk, "full_crossing", lambda *a, **k: None)   # the secant left it
    assert pk.pk_crossing(section(), 80.33, 44.1j, lo=79.0, hi=81.0) is None


def test_a_sweep_on_the_full_dofs_converges_its_crossings_to_a_tenth_of_xtol():
    """Patil's wing over 5-200 m/s (swept on its full DOFs: its basis fails the check): each
    crossing by the secant from its bracket's ends, to xtol / 10 (Brent's method, to xtol,
    was 0.0017 m/s off the flutter onset at 32.518 m/s), against the same sweep to 1e-5."""
    from propwhirl.cases.ch07_patil import patil_model
    V = np.linspace(5.0, 200.0, 12)
    got = pk_sweep(patil_model(), V)
    ref = pk_sweep(patil_model(), V, xtol=1e-5)
    assert got.basis_size == 0 and len(got.flutter) == len(ref.flutter) >= 4
    for a, b in zip(got.flutter, ref.flutter):
        assert (a.kind, a.event) == (b.kind, b.event)
        assert a.V == pytest.approx(b.V, abs=0.1 * 0.01)


def test_the_secant_in_a_bracket_leaves_a_hop_to_brents_method(monkeypatch):
    """_secant_in on two branches with a jump between them (Re p of opposite signs, the
    x57_like values) converges onto the jump and says so (None): _bracketed then decides."""
    from propwhirl.analysis import pk_crossings as pk

    def solve(V, p0):
        if V < 80.3311:
            return complex(-0.0144 + 0.015 * (V - 80.3311), 44.095), 0.2
        return complex(0.0034 + 0.015 * (V - 80.3311), 44.146), 0.2

    for a, b in ((78.0, 81.1), (78.0, 82.3), (78.3, 81.0)):   # without the check the secant
        pa, pb = solve(a, 0)[0], solve(b, 0)[0]                # converged onto the jump here
        bracket = (a, b, pa, pb, pa.real, pb.real)
        assert pk._secant_in(solve, bracket, 0.01, 44.1, True) is None
