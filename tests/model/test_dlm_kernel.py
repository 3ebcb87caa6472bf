"""The doublet-lattice kernel on the half-wing's rows (issue 37, item 2): PanelAero's AIC to
round-off, half the kernel, once per Mach column what every k shares.

``dlm.Kernel`` computes the symmetric AIC Q_RR + Q_RL = −(A_RR + A_RL)⁻¹ from the right
half-wing's rows of the normalwash matrix (``dlm_kernel.steady_rows``: PanelAero's VLM, the same
bits; ``dlm_kernel.PlanarKernel``: PanelAero's parabolic DLM increment, planar part, its
k-independent parts once); PanelAero's own ``calc_Qjj`` of the whole mirrored wing, folded, is
the reference (what propwhirl computed before, ``dlm.symmetric_aic``).  Measured: 2e-15 of
max |Q| (x57_like, 8 x 37 panels); asserted 1e-12 (a factorisation of a 296 x 296 or 592 x 592
matrix in another order: round-off, not a tolerance of the method)."""
import copy

import numpy as np
import pytest

pytest.importorskip("panelaero")

from propwhirl.model.aerodynamics import dlm, dlm_kernel  # noqa: E402
from propwhirl.model.structure.wing import Wing  # noqa: E402

ROUND_OFF = 1e-12
POINTS = ((0.0, 0.0), (0.0, 0.3), (0.3, 0.05), (0.3, 1.2), (0.65, 0.4), (0.85, 2.0))


def wing(**kw):
    base = dict(semi_span=3.0, mass_per_length=1.0, EI=1e4, GJ=1e4, radius_of_gyration=0.25,
                n_elements=4, aero="dlm", dlm_chordwise_panels=3, dlm_spanwise_panels=5)
    return Wing(**{**base, **kw})


def panelaero_sym(aero, mach, k):
    from panelaero import DLM
    n = aero.mesh.n
    with np.errstate(all="ignore"):
        Q = DLM.calc_Qjj(copy.deepcopy(aero.grid), mach, k / aero.b_ref)
    return Q[n:, n:] + Q[n:, :n]


@pytest.mark.parametrize("shape", [{}, {"root_chord": 1.0, "tip_chord": 0.4}])
def test_the_symmetric_aic_is_panelaeros_to_round_off(shape):
    aero = dlm.DlmAerodynamics(wing(**shape))
    assert aero.planar
    for mach, k in POINTS:
        ref = panelaero_sym(aero, mach, k)
        got = aero.aic(mach, k)
        assert np.abs(got - ref).max() <= ROUND_OFF * np.abs(ref).max(), (mach, k)


def test_the_steady_rows_are_panelaeros_vlm_bit_for_bit():
    from panelaero import VLM
    aero = dlm.DlmAerodynamics(wing())
    n = aero.mesh.n
    for mach in (0.0, 0.3, 0.8):
        with np.errstate(all="ignore"):
            full = VLM.calc_Ajj(aerogrid=copy.deepcopy(aero.grid), Ma=mach)[0]
            rows = dlm_kernel.steady_rows(aero.grid, mach, slice(n, None))
        assert np.array_equal(rows, full[n:])


def test_the_planar_increment_is_panelaeros_rows():
    from panelaero import DLM
    aero = dlm.DlmAerodynamics(wing(dlm_chordwise_panels=4, dlm_spanwise_panels=6))
    n = aero.mesh.n
    for mach, kbar in ((0.0, 0.2), (0.5, 0.7), (0.8, 3.0)):
        with np.errstate(all="ignore"):
            ref = DLM.calc_Ajj(aerogrid=copy.deepcopy(aero.grid), Ma=mach, k=kbar,
                               method="parabolic")[n:]
        got = dlm_kernel.PlanarKernel(aero.grid, mach, slice(n, None)).increment(kbar)
        assert np.abs(got - ref).max() <= ROUND_OFF * np.abs(ref).max()


def dihedral(grid, slope=0.2):
    """``grid`` with every point raised by ``slope`` |y| (a V-shaped, non-planar wing)."""
    g = copy.deepcopy(grid)
    for key in ("offset_l", "offset_k", "offset_j", "offset_P1", "offset_P3"):
        g[key][:, 2] = slope * np.abs(g[key][:, 1])
    N = np.column_stack([np.zeros(g["n"]), -slope * np.sign(g["offset_k"][:, 1]),
                         np.ones(g["n"])])
    g["N"] = N / np.linalg.norm(N, axis=1)[:, None]
    return g


def test_a_non_planar_mesh_takes_panelaeros_whole_kernel_folded():
    from panelaero import DLM
    aero = dlm.DlmAerodynamics(wing())
    n = aero.mesh.n
    g = dihedral(aero.grid)
    assert not dlm_kernel.is_planar(g, slice(n, None))
    for mach, kbar in ((0.0, 0.0), (0.3, 0.4), (0.7, 1.5)):
        with np.errstate(all="ignore"):
            Q = DLM.calc_Qjj(copy.deepcopy(g), mach, kbar)
        ref = Q[n:, n:] + Q[n:, :n]
        got = dlm.Kernel(g, n, mach, planar=False).aic(kbar)
        assert np.abs(got - ref).max() <= ROUND_OFF * np.abs(ref).max()


def test_one_kernel_per_mach_column_and_no_panelaero_dlm_call_on_a_planar_mesh(monkeypatch):
    """Work, not time: filling 8 reduced frequencies at 2 Mach numbers builds 2 kernels (the
    k-independent parts once per column) and computes 16 AICs; PanelAero's whole-wing DLM
    kernel (``calc_Ajj``, (2n)² entries per k) is never called on a planar mesh."""
    from panelaero import DLM
    built, whole = [], []
    real = dlm.Kernel.__init__

    def counted(self, *args, **kw):
        built.append(args[2])
        real(self, *args, **kw)

    monkeypatch.setattr(dlm.Kernel, "__init__", counted)
    monkeypatch.setattr(DLM, "calc_Ajj", lambda *a, **k: whole.append(1))
    aero = dlm.DlmAerodynamics(wing())
    nodes = [(m, ik) for m in (0.3, 0.5) for ik in (0, 3, 6, 9, 12, 15, 17, 19)]
    assert aero.fill(nodes) == 16
    assert aero.evaluations == 16 and built == [0.3, 0.5] and whole == []


def test_the_kernels_kept_are_bounded():
    aero = dlm.DlmAerodynamics(wing())
    for mach in (0.1, 0.2, 0.3, 0.4):
        aero.aic(mach, 0.5)
    assert len(aero._kernels) == dlm.KERNELS
    assert tuple(aero._kernels) == (0.3, 0.4)[-dlm.KERNELS:]


def test_the_answer_moves_by_round_off_only():
    """The Goland wing's DLM flutter (4 x 7 panels, Mach 0, p-k) with the kernel on the half-wing's
    rows against PanelAero's whole kernel (``dlm.symmetric_aic``) in every AIC."""
    from propwhirl.analysis.pk import pk_flutter
    from propwhirl.model import FlightCondition, PropellerWing
    w = Wing(semi_span=6.096, root_chord=1.8288, mass_per_length=35.71, polar_inertia=8.64,
             EI=9.77e6, GJ=0.987e6, elastic_axis=0.33, centre_of_gravity=0.43, n_elements=10,
             aero="dlm", dlm_mach=0.0, dlm_chordwise_panels=4, dlm_spanwise_panels=7)
    model = PropellerWing(w, FlightCondition(1.02))
    speeds = np.arange(150.0, 181.0, 10.0)
    new = pk_flutter(model, speeds, n_modes=4, tables=dlm.DlmTables(processes=1))

    class Whole(dlm.Kernel):
        def aic(self, kbar):
            return dlm.symmetric_aic(self.grid, self.n, self.mach, kbar)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(dlm, "Kernel", Whole)
        old = pk_flutter(model, speeds, n_modes=4, tables=dlm.DlmTables(processes=1))
    assert [e.kind for e in new] == [e.kind for e in old] and len(new) >= 1
    for a, b in zip(new, old):
        assert a.V == pytest.approx(b.V, abs=1e-6) and a.frequency == pytest.approx(b.frequency,
                                                                                   rel=1e-9)


def swept(grid, tan_sweep=0.6):
    """``grid`` with every point moved aft by ``tan_sweep`` |y| (a swept planar wing, both
    halves)."""
    g = copy.deepcopy(grid)
    for key in ("offset_l", "offset_k", "offset_j", "offset_P1", "offset_P3"):
        g[key][:, 0] = g[key][:, 0] + tan_sweep * np.abs(g[key][:, 1])
    return g


def test_a_swept_planar_mesh_is_panelaeros_to_round_off():
    """The sweep enters through tan Λ of each doublet line (x − e tan Λ, R, u₁): a planar
    wing swept back 31° (e.g. a planform of another shape than the beam's) still within
    round-off of PanelAero's whole kernel folded."""
    from panelaero import DLM
    aero = dlm.DlmAerodynamics(wing(dlm_chordwise_panels=4, dlm_spanwise_panels=6))
    n = aero.mesh.n
    g = swept(aero.grid)
    assert dlm_kernel.is_planar(g, slice(n, None))
    for mach, kbar in ((0.0, 0.0), (0.4, 0.3), (0.8, 2.0)):
        with np.errstate(all="ignore"):
            Q = DLM.calc_Qjj(copy.deepcopy(g), mach, kbar)
        ref = Q[n:, n:] + Q[n:, :n]
        got = dlm.Kernel(g, n, mach, planar=True).aic(kbar)
        assert np.abs(got - ref).max() <= ROUND_OFF * np.abs(ref).max()
