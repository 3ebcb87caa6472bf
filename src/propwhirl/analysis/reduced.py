"""The analysis of large models: reduced-order tracking, full-order crossings.

:func:`choose_method` decides between the dense full-order engine (``"dense"``: the reference,
every root of A(V), cost O(n³) per speed) and the reduced one (``"reduced"``), by size: models
of more than :data:`REDUCED_ABOVE` states that can be reduced (a
:class:`~propwhirl.model.systems.PropellerWing`) are reduced.  Every thesis model is below it.

:func:`reduced_engine_analysis` runs the engine's tracker and crossing refinement on the
:class:`~propwhirl.model.reduction.ReducedModel` (states 2r + L instead of 2n + m), then
corrects every crossing on the full-order sparse pencil
(:func:`propwhirl.engine.correction.correct_crossing`) and lifts the tracked eigenvectors to the
full state lazily (:class:`LiftedEigenvectors`: kept as reduced vectors, r + L entries each, and
lifted only where a result is read — the mode names at the first speed, the mode shapes of the
events, a saved file with eigenvectors).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.engine import analyse as engine_analyse
from propwhirl.engine import single_thread_blas
from propwhirl.engine.correction import correct_crossing, full_order_pair
from propwhirl.engine.results import Analysis, Criticals
from propwhirl.model.aerodynamics.dlm import require_panelaero
from propwhirl.model.aerodynamics.dlm_surface import surface_of
from propwhirl.model.protocol import capabilities
from propwhirl.model.reduction import CUTOFF_FACTOR, ReducedModel, reduce

#: models with more states than this were analysed reduced by default (``method="auto"``)
#: before issue 26; ``"auto"`` now reduces every reducible model (kept for scripts that read it)
REDUCED_ABOVE = 400
#: what ``method="auto"`` asks of a reduced analysis to keep it (else the model is analysed
#: again, dense): every crossing converged on the full-order model, and every frequency-zero
#: event's bracket holding the full-order model's branch point
#: (:func:`frequency_zero_on_full_order`)
AUTO_NEEDS = ("every crossing converged on the full order, every frequency-zero bracket "
              "holding the full order's branch point")
METHODS = ("auto", "dense", "reduced", "pk")


def choose_method(model, method: str) -> str:
    """"dense", "reduced" or "pk" for ``method`` ("auto", "dense", "reduced" or "pk": the
    p-k method with the exact Theodorsen function, typical sections and wings) and ``model``.
    A wing with ``aero = "dlm"`` (doublet-lattice loads): "auto" is "reduced", its modal
    Roger state space with every crossing converged by the p-k method
    (:mod:`propwhirl.analysis.modal_dlm`), "dense" the Roger state space on every DOF
    (:mod:`propwhirl.model.aerodynamics.dlm_rfa`: every structural mode, also those far beyond the fit's
    reduced frequencies), "pk" the p-k method on Q(k).

    Examples
    --------
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> choose_method(wingtip_propeller_wing(), "auto")      # a wing: reduced, checked after
    'reduced'
    >>> choose_method(wingtip_propeller_wing(), "dense")     # the reference
    'dense'
    """
    if method not in METHODS:
        raise v.InputError(f"method = {method!r} is invalid: must be one of "
                           f"{', '.join(repr(m) for m in METHODS)}")
    can = capabilities(model)       # the model says what it runs, and why not
    why = can.refusal(method) if method != "auto" else None
    if why is not None:
        raise v.InputError(f"method = {method!r} is invalid for this model: {why}")
    dlm = can.aerodynamics == "doublet lattice"
    if dlm:
        require_panelaero()                 # before the finite-state tracking starts
        # one AIC of its panels within the memory limit, before any is built
        limits.check_panels(*surface_of(model).planform.counts())
    if method == "pk":
        return "pk"
    if dlm:                 # the modal Roger state space, its crossings the p-k's
        return "dense" if method == "dense" else "reduced"
    if method == "auto":
        return "reduced" if can.supports("reduced") else "dense"
    return method


class LiftedEigenvectors:
    """Eigenvectors ``(T, n_full, n_modes)`` kept in reduced coordinates and lifted on access.

    Indexing like the array (``X[t]``, ``X[t, :, k]``, ``X[0][mask]``) lifts only the speeds
    asked for; ``np.asarray(X)`` lifts all (a saved file with eigenvectors).
    """

    def __init__(self, reduced: np.ndarray, lift: np.ndarray) -> None:
        self.reduced = reduced
        self.lift = lift

    @property
    def shape(self) -> tuple[int, int, int]:
        T, _, k = self.reduced.shape
        return (T, self.lift.shape[0], k)

    ndim = 3
    dtype = np.dtype(complex)

    def __len__(self) -> int:
        return self.reduced.shape[0]

    def __getitem__(self, index):
        if not isinstance(index, tuple):
            index = (index,)
        t, rest = index[0], index[1:]
        Xr = self.reduced[t]                                  # (..., n_r, k)
        full = np.matmul(self.lift, Xr)
        if not rest:
            return full
        lead = (slice(None),) * (full.ndim - 2)
        return full[lead + tuple(rest)]

    def __array__(self, dtype=None, copy=None):
        out = np.matmul(self.lift, self.reduced)
        return out if dtype is None else out.astype(dtype)


@dataclass(frozen=True)
class ReducedRun:
    """What :func:`reduced_engine_analysis` returns: the engine Analysis (lifted sweep,
    corrected crossings), the reduced model, and per crossing the correction [m/s] (the
    truncation error of the reduced model at that crossing; None where it failed)."""

    analysis: Analysis
    model: ReducedModel
    corrections: tuple[float | None, ...]


def reduced_engine_analysis(model, grid: np.ndarray, *, displacement, state_labels,
                            options=None, xtol: float, vgf: bool = False,
                            cutoff_hz: float | None = None,
                            factor: float = CUTOFF_FACTOR, assembly=None,
                            structure: tuple[np.ndarray, np.ndarray] | None = None
                            ) -> ReducedRun:
    """The engine on the reduced model, crossings corrected on the full order (module doc).
    BLAS at one thread throughout (the basis, the engine, the sparse solves).  ``assembly`` and
    ``structure``: the model's assembly and its structural (M, K), if already built
    (:func:`~propwhirl.model.reduction.reduce`)."""
    with single_thread_blas():
        return _reduced_engine_analysis(model, grid, displacement, state_labels, options, xtol,
                                        vgf, cutoff_hz, factor, assembly, structure)


def _reduced_engine_analysis(model, grid, displacement, state_labels, options, xtol, vgf,
                             cutoff_hz, factor, assembly, structure) -> ReducedRun:
    R = reduce(model, grid, cutoff_hz=cutoff_hz, factor=factor, assembly=assembly,
               structure=structure)
    # the reduced crossings to xtol/10 (cheap: inverse iterations on the small model), so that
    # the full-order correction of a crossing is one evaluation where the truncation error is
    # below xtol/10 (engine/correction.py) — on the wingtip model every crossing
    an = engine_analyse(R.state_matrix, grid, displacement=R.displacement,
                        state_labels=R.labels(), options=options, xtol=0.1 * xtol,
                        **({"initial_step": None} if vgf else {}))
    lift = R.lift
    points, shifts = [], []
    slopes = _reduced_slopes(an.sweep, an.criticals.points)
    for p, slope in zip(an.criticals.points, slopes):
        x0 = lift @ p.eigenvector
        c = correct_crossing(R.pencil, p.V, p.eigenvalue, x0, xtol=xtol, slope=slope)
        if c is None:
            points.append(replace(p, eigenvector=x0 / np.linalg.norm(x0)))
            shifts.append(None)
            continue
        shifts.append(c.V - p.V)
        half = 0.5 * (p.bracket[1] - p.bracket[0])
        points.append(replace(p, V=c.V, bracket=(c.V - half, c.V + half),
                              eigenvalue=c.eigenvalue, eigenvector=c.eigenvector,
                              frequency_hz=abs(c.eigenvalue.imag) / (2 * np.pi)))
    stats = dict(an.criticals.stats)
    stats["corrected"] = sum(s is not None for s in shifts)
    crit = Criticals(tuple(points), an.criticals.humps, an.criticals.unstable_at_start, stats)
    sw = an.sweep
    sw_stats = dict(sw.stats, reduced_states=R.n_states, reduced_r=R.basis.r,
                    reduced_L=R.basis.L)
    lifted = replace(sw, eigenvectors=LiftedEigenvectors(sw.eigenvectors, lift),
                     state_labels=tuple(state_labels), displacement=np.asarray(displacement),
                     stats=sw_stats)
    return ReducedRun(Analysis(lifted, crit), R, tuple(shifts))


def frequency_zero_on_full_order(points, shapes, reduced: ReducedModel) -> bool:
    """Whether every frequency-zero event ``points`` of the ``reduced`` model (brackets of width
    ≤ xtol, :func:`propwhirl.engine.frequency_zero_points`) is one of the full-order model too:
    the full-order pair turns real inside each bracket, so its branch point lies within xtol of
    the event's speed.

    ``shapes``: each event's (eigenvector lifted to the full state, λ, V) at the bracket's lower
    end, the pair's root there
    (:func:`~propwhirl.analysis.participation.branch_point_shape`, which also gives the event
    its shape).  Its λ's real part is the shift σ and the real and imaginary parts of its
    vector the start of :func:`~propwhirl.engine.correction.full_order_pair` on the full-order
    sparse pencil at each bracket end: a complex pair with Re λ > 0 at the lower end and two
    real roots at the upper end (the count of unstable complex pairs falls there, as the event
    says).  Two sparse factorisations of the full pencil per event; False where the root at the
    lower end is not an unstable complex one or the iteration does not converge (auto then
    analyses the model dense)."""
    with single_thread_blas():
        for p, (x, lam, _) in zip(points, shapes, strict=True):
            if not _unstable_complex(np.array([lam]))[0]:
                return False
            start = np.column_stack([np.real(x), np.imag(x)])
            ends = [full_order_pair(*reduced.pencil(V), float(np.real(lam)), start)
                    for V in p.bracket]
            if any(mu is None for mu in ends):
                return False
            lo, hi = ends
            if not (_unstable_complex(lo).any() and np.all(hi.imag == 0)):
                return False
    return True


def _unstable_complex(lam: np.ndarray) -> np.ndarray:
    """Which roots ``lam`` are unstable with Im λ > 0, as the engine's frequency-zero search
    counts them (Re λ > 0, Im λ > 1e-9 max(1, |λ|))."""
    return (lam.real > 0) & (lam.imag > 1e-9 * np.maximum(1.0, np.abs(lam)))


def _reduced_slopes(sweep, points) -> list[float | None]:
    """d Re λ/dV [1/m] of each crossing's reduced root: the tracked dλ/dV of its mode at the
    two sweep speeds around the crossing, interpolated linearly in V (no new evaluation)."""
    out: list[float | None] = []
    V = sweep.V
    for p in points:
        t = int(np.clip(np.searchsorted(V, p.V) - 1, 0, V.size - 2))
        g = sweep.dlam_dV[t:t + 2, p.mode].real
        w = (p.V - V[t]) / (V[t + 1] - V[t]) if V[t + 1] > V[t] else 0.5
        s = float((1 - w) * g[0] + w * g[1])
        out.append(s if np.isfinite(s) and s != 0 else None)
    return out
