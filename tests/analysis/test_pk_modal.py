"""The p-k sweep on a Galerkin basis (issue 37 item 2: modal reduction for the p-k).

A beam wing's p-k sweep iterates on the default's reduced basis Φ (in-vacuo modes up to the
cut-off and the static correction vectors) and converges every crossing it finds on the full
DOFs. Its crossings are the full-order sweep's (``pk_sweep(modal=False)``) to xtol: same modes,
directions and kinds, speeds within XTOL = 0.01 m/s (Brent's own accuracy on the full path),
frequencies within 1e-4 (relative). The work is bounded by counting the eigenproblems of the
model's full size: the full-order sweep solves one per mode, speed and k iteration; the modal
one only those of the check of its basis at the top speed (pk_basis.basis_error) and of the
full-order convergence of its crossings.

Measured (full-size eigenproblems of the sweep, modal / full order): Goland strips 17 / 370,
wingtip model on strips 18 / 279, the 6-element wingtip wing on 3 × 8 panels at Mach 0.6
27 / 233 and Mach-matched 40 / 868 (each crossing converged at its own Mach: the secant from
the reduced crossing on the tables' Mach interpolation, up to 28 m/s away on the
forward-whirl hump, as matched_crossing from the full-order one); before the k iteration's
secant steps, the p-k's own basis, the brackets' interpolated starts and the tight clusters'
shorter steps: 19 / 444, 21 / 388, 35 / 315, 91 / 909."""
import dataclasses

import numpy as np
import pytest

from propwhirl.analysis import pk, pk_basis
from propwhirl.analysis.pk import XTOL, pk_sweep
from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
from propwhirl.model import FlightCondition, PropellerWing, Wing
from propwhirl.model.frequency_domain import pk_system


def goland(**kw) -> PropellerWing:
    """Goland's wing (10 elements) at sea level."""
    wing = Wing(semi_span=6.096, root_chord=1.8288, mass_per_length=35.71, polar_inertia=8.64,
                EI=9.77e6, GJ=0.987e6, elastic_axis=0.33, centre_of_gravity=0.43,
                n_elements=10, **kw)
    return PropellerWing(wing, FlightCondition(1.225), name="goland")


def small_wingtip(mach) -> PropellerWing:
    """The thesis's wingtip model on 6 elements and 3 × 8 panels."""
    m = wingtip_propeller_wing()
    return m.with_(wing=dataclasses.replace(m.wing, n_elements=6, aero="dlm", dlm_mach=mach,
                                            dlm_chordwise_panels=3, dlm_spanwise_panels=8))


def counted(monkeypatch, n_full: int) -> list[int]:
    """Count the first-order matrices of the model's full size (2 n_full) the k iterations
    solve (a stack of several modes' counts each)."""
    sizes: list[int] = []
    real = pk_basis.first_order

    def first_order(system, omega):
        A = real(system, omega)
        sizes.extend([A.shape[-1]] * (A.shape[0] if A.ndim == 3 else 1))
        return A

    monkeypatch.setattr(pk_basis, "first_order", first_order)
    return sizes


def same_crossings(modal, full):
    assert [(e.mode, e.event, e.kind) for e in modal.flutter] == \
        [(e.mode, e.event, e.kind) for e in full.flutter]
    for a, b in zip(modal.flutter, full.flutter):
        assert a.V == pytest.approx(b.V, abs=XTOL)
        assert a.frequency == pytest.approx(b.frequency, rel=1e-4, abs=1e-6)
        assert a.shift is not None and b.shift is None


CASES = {
    "goland strips": (lambda: goland(), np.arange(120.0, 271.0, 10.0), 30),
    "wingtip propeller wing": (wingtip_propeller_wing, np.linspace(100.0, 200.0, 11), 30),
}
DLM_CASES = {
    "wingtip 3x8 Mach 0.6": (lambda: small_wingtip(0.6), np.arange(140.0, 231.0, 10.0), 50),
    "wingtip 3x8 matched": (lambda: small_wingtip("speed"), np.arange(140.0, 231.0, 10.0), 120),
}


def _compare(monkeypatch, make, speeds, most):
    model = make()
    n = model.dof_map().n_dof
    sizes = counted(monkeypatch, n)
    modal = pk_sweep(model, speeds)
    full_size_modal = sizes.count(2 * n)
    sizes.clear()
    full = pk_sweep(model, speeds, modal=False)
    full_size_full = sizes.count(2 * n)
    assert modal.flutter, "a case with crossings"
    assert 0 < modal.basis_size < n and full.basis_size == 0
    same_crossings(modal, full)
    # the full-size eigenproblems: only the crossings' convergence (measured: module docstring)
    assert full_size_modal <= most
    assert full_size_full > 5 * full_size_modal


@pytest.mark.parametrize("case", sorted(CASES))
def test_modal_sweep_crossings_are_the_full_order_sweeps(monkeypatch, case):
    _compare(monkeypatch, *CASES[case])


@pytest.mark.parametrize("case", sorted(DLM_CASES))
def test_modal_sweep_crossings_are_the_full_order_sweeps_on_panels(monkeypatch, case):
    pytest.importorskip("panelaero")
    _compare(monkeypatch, *DLM_CASES[case])


def _projection_is_exact(model, speeds, tables=None):
    basis = pk_basis.pk_basis(model, speeds, tables)
    Phi = basis.Phi
    for V, omega in ((float(speeds[0]), 30.0), (float(speeds[-1]), 111.0)):
        full = pk_system(model, V, tables)(omega)
        reduced = pk_system(model, V, tables, basis=basis)(omega)
        for X, Xr in zip(full, reduced):
            assert Xr == pytest.approx(Phi.T @ X @ Phi, rel=1e-10, abs=1e-9 * np.abs(Xr).max())


def test_projected_strips_are_the_projection_of_the_full_system():
    """Φᵀ (M, C(ω), K(ω)) Φ of the full p-k system, built strip by strip on Φ's rows."""
    model = wingtip_propeller_wing()
    _projection_is_exact(model, np.array([100.0, 200.0]))


def test_projected_tables_are_the_projection_of_the_full_system():
    """A doublet-lattice wing's Q tables projected once interpolate (cubic in k, linear in
    Mach) to the projection of the full Q: the interpolation commutes with it."""
    pytest.importorskip("panelaero")
    from propwhirl.model.aerodynamics.dlm import DlmTables
    _projection_is_exact(small_wingtip("speed"), np.array([140.0, 212.0]), DlmTables())


def test_the_basis_holds_the_followed_modes_and_only_a_beam_wing_has_one():
    """The basis spans the in-vacuo modes the sweep follows (one place for that choice:
    followed_modes) and their static correction under the p-k's steady loads,
    M-orthonormal; a typical section is swept on its own DOFs."""
    import scipy.linalg as sla
    from propwhirl.analysis.modes import InVacuo
    from propwhirl.model import TypicalSection
    from propwhirl.model.frequency_domain import pk_system as system
    model = wingtip_propeller_wing()
    V = np.linspace(100.0, 200.0, 11)
    basis = pk_basis.pk_basis(model, V)
    Phi = basis.Phi
    iv = InVacuo.of(model.without_aerodynamics())
    M = iv.M                                            # the structure's mass
    assert Phi.T @ M @ Phi == pytest.approx(np.eye(basis.r), abs=1e-9)
    n = pk_basis.followed_modes(model, V)
    _, shapes = sla.eigh(iv.K, M)
    top = sla.solve(iv.K, (system(model, 200.0)(0.0)[2] - iv.K) @ shapes[:, :n])
    from propwhirl.model.reduction import GRAM_TOL
    for D in (shapes[:, :n], top):        # in the span of Φ (unit vectors: up to the
        D = D / np.sqrt(np.einsum("ij,ij->j", D, M @ D))    # √GRAM_TOL of a dropped one)
        residual = D - Phi @ (Phi.T @ M @ D)
        assert np.abs(residual).max() < 10 * np.sqrt(GRAM_TOL)
    assert n < basis.r <= 3 * n
    more = pk_basis.pk_basis(model, V, n_modes=n + 2)   # the modes a caller asks for
    assert more.r > basis.r
    sec = TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=np.sqrt(0.24),
                         m=20 * np.pi * 1.225, omega_h=20.0, omega_alpha=50.0,
                         flight=FlightCondition(1.225))
    assert pk_basis.pk_basis(sec, V) is None
    assert pk_sweep(sec, np.linspace(5.0, 200.0, 40)).basis_size == 0


def test_batched_roots_are_each_modes_own(monkeypatch):
    """pk_roots of several modes at once gives each the root pk_root gives it alone."""
    model = wingtip_propeller_wing()
    V = 150.0
    start, _ = pk._start_roots(model, V, 7)
    system = pk_system(model, V)
    together, kt = pk_basis.pk_roots(model, V, start, system, ktol=pk.KTOL)
    for p0, p, k in zip(start, together, kt):
        q, kq = pk.pk_root(model, V, p0, system=system)
        assert p == q and k == kq


def _systems():
    model = wingtip_propeller_wing()
    V = np.array([100.0, 200.0])
    basis = pk_basis.pk_basis(model, V)
    from propwhirl.model import TypicalSection
    sec = TypicalSection(b=1.0, a=-0.2, x_alpha=0.1, r_alpha=np.sqrt(0.24),
                         m=20 * np.pi * 1.225, omega_h=20.0, omega_alpha=50.0,
                         flight=FlightCondition(1.225))
    return {"strips, full DOFs": pk_system(model, 150.0),
            "strips, on the basis": pk_system(model, 150.0, basis=basis),
            "typical section": pk_system(sec, 50.0)}


def _dlm_systems():
    pytest.importorskip("panelaero")
    from propwhirl.model.aerodynamics.dlm import DlmTables
    model, tables = small_wingtip(0.6), DlmTables()
    basis = pk_basis.pk_basis(model, np.array([140.0, 230.0]), tables)
    return {"panels, full DOFs": pk_system(model, 180.0, tables),
            "panels, on the basis": pk_system(model, 180.0, tables, basis=basis)}


@pytest.mark.parametrize("name", ["strips, full DOFs", "strips, on the basis",
                                  "typical section", "panels, full DOFs",
                                  "panels, on the basis"])
def test_a_system_over_several_frequencies_is_each_frequencys(name):
    """ω an array: the matrices of every ω stacked, each equal to the one-ω call (the k
    iteration of all followed modes builds them together; the doublet lattice's projected
    tables interpolated in k for all of them at once)."""
    system = (_dlm_systems() if name.startswith("panels") else _systems())[name]
    omegas = np.array([3.0, 30.0, 111.0])
    stacked = system(omegas)
    A = pk_basis.first_order(system, omegas)
    for i, w in enumerate(omegas):
        for X, Xs in zip(system(w), stacked):
            assert Xs[i] == pytest.approx(X, rel=1e-13, abs=1e-12 * np.abs(X).max())
        assert A[i] == pytest.approx(pk_basis.first_order(system, w), rel=1e-12, abs=1e-9)


def test_the_secant_converges_to_the_plain_iterations_root_in_fewer_steps(monkeypatch):
    """The secant steps of the k iteration reach the fixed point the plain steps reach (to the
    iteration's tolerance) with fewer eigenproblems (measured at 150 m/s from the start roots
    of 8 modes, batched solves and matrices plain / secant: the Goland wing 7 and 26 / 5 and
    22, the wingtip wing 7 and 29 / 4 and 23; in the sweeps, where each speed starts from the
    last, 5-9 steps became 3-4)."""
    calls = []
    real = pk_basis.first_order
    monkeypatch.setattr(pk_basis, "first_order",
                        lambda system, omega: calls.append(np.size(omega)) or real(system, omega))
    for model in (goland(), wingtip_propeller_wing()):
        V = 150.0
        start, _ = pk._start_roots(model, V, 8)
        system = pk_system(model, V)
        calls.clear()
        plain, kp = pk_basis.pk_roots(model, V, start, system, ktol=pk.KTOL, secant=False)
        n_plain, sum_plain = len(calls), sum(calls)
        calls.clear()
        fast, kf = pk_basis.pk_roots(model, V, start, system, ktol=pk.KTOL)
        assert np.all(np.isfinite(kf)) and np.all(np.isfinite(kp))
        assert fast == pytest.approx(plain, rel=10 * pk.KTOL)
        assert kf == pytest.approx(kp, rel=10 * pk.KTOL)
        assert len(calls) < n_plain and sum(calls) < sum_plain


def test_the_structure_is_assembled_once_per_sweep_not_per_speed(monkeypatch):
    """The p-k system adds its loads to the structure and propellers assembled once
    (frequency_domain.dry_assembly), not at each speed, Brent step and k iteration: the
    Goland wing's sweep over 16 speeds assembled 77 times before, 8 now (the finite-state
    start roots, the bases and the one dry assembly)."""
    from propwhirl.model import systems
    calls = []
    real = systems.PropellerWingAssembly.build.__func__
    monkeypatch.setattr(systems.PropellerWingAssembly, "build", classmethod(
        lambda cls, *a, **k: calls.append(1) or real(cls, *a, **k)))
    sweep = pk_sweep(goland(), np.arange(120.0, 271.0, 10.0))
    assert sweep.flutter
    assert len(calls) <= 8


def test_the_basis_check_is_the_full_roots_at_the_reduced_roots_k():
    """basis_error compares each reduced root with the full model's root at that root's own
    k (one batched eigensolve): where the basis holds, that is the root the full model's k
    iteration converges to from it, within the basis's own error."""
    model = goland()
    V = np.arange(120.0, 271.0, 10.0)
    basis = pk_basis.pk_basis(model, V)
    top = float(V[-1])
    start, _ = pk._start_roots(model, top, 8)
    reduced, _ = pk_basis.pk_roots(model, top, start, pk_system(model, top, basis=basis),
                                   ktol=pk.KTOL)
    full, _ = pk_basis.pk_roots(model, top, reduced, pk_system(model, top), ktol=pk.KTOL)
    ratio, relative = pk_basis.basis_error(model, top, reduced)
    iterated = np.max(np.abs(reduced - full) / np.abs(full))
    assert 0 < relative < pk_basis.BASIS_REL and ratio < pk_basis.BASIS_TOL
    assert relative == pytest.approx(iterated, rel=0.01)    # measured: 1.7683e-5 vs 1.7687e-5


def test_a_basis_that_does_not_hold_the_roots_leaves_the_sweep_to_the_full_dofs():
    """Patil's HALE wing at 5.4 times its divergence speed: its reduced roots are ~100 %
    off the full ones at the top speed (measured: 0.96 of |p|, 1.05 of the distance to the
    nearest other root) — the sweep runs on the full DOFs (there the reduced sweep missed a
    divergence the full one has)."""
    from propwhirl.cases.ch07_patil import patil_model
    assert pk_sweep(patil_model(), np.linspace(5.0, 200.0, 12)).basis_size == 0
