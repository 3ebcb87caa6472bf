"""Brute-force oracles of the stability engine (test helpers, not part of the package).

The thesis's method (§5.2.1, §5.2.3) and exact checks, independent of the engine's tracking:

* :func:`fixed_grid_sweep` — a full eigendecomposition of A(V) at every speed of a fixed grid
  (ΔV = 1 m/s from 1 to 350 m/s by default, :data:`THESIS_SPEEDS`), each part timed;
* :func:`detect_crossings` — sign changes of Re λ between consecutive speeds (the thesis's
  detection, accuracy ± one grid step), kind and frequency, frequency-zero events;
* :func:`converge_crossing` — the converged location of one crossing by bisection on the exact
  number of eigenvalues with Re λ > 0 (:func:`count_unstable`, a full ``eigvals`` per step);
* :func:`engine_crossings`, :func:`match_crossings` — the engine's crossings as
  :class:`Crossing` records and a one-to-one matching of two crossing lists.

Used by the tests of the engine on the real model (``from helpers.brute_force import ...``) and
by ``benchmarks/engine_vs_fixed_grid.py`` (method (b) of docs/performance.md).
"""
from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import linear_sum_assignment
from threadpoolctl import threadpool_limits

from propwhirl import validate as v

__all__ = [
    "THESIS_SPEEDS", "Crossing", "Timing", "FixedGridResult", "fixed_grid_sweep",
    "detect_crossings", "count_unstable", "converge_crossing", "engine_crossings",
    "match_crossings",
]

#: The thesis's sweep: ΔV = 1 m/s from 1 to 350 m/s (§5.2.1; 0–350 m/s in chapters 9–11) [m/s]
THESIS_SPEEDS = np.arange(1.0, 351.0, 1.0)


# ----------------------------------------------------------------------------------------------
# Crossings
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Crossing:
    """One critical point: a sign change of Re λ or an unstable pair turning real.

    kind:         "flutter" (complex pair crosses) or "divergence" (real root through zero, or
                  an unstable pair whose frequency falls to zero).
    event:        "onset" (Re λ − → +), "recovery" (+ → −) or "frequency-zero".
    V:            speed [m/s] (engine: refined value; fixed grid: Re λ interpolated linearly
                  inside the bracket).
    frequency_hz: |Im λ|/2π at V [Hz] (0 for divergence).
    bracket:      (lo, hi) [m/s] known to contain the event.
    label:        mode name where known.
    """

    kind: str
    event: str
    V: float
    frequency_hz: float
    bracket: tuple[float, float]
    label: str = ""


@dataclass
class Timing:
    """Wall-clock and process-CPU time [s] of one measured task."""

    wall: float
    cpu: float

    @classmethod
    def measure(cls, fn: Callable[[], Any]) -> tuple["Timing", Any]:
        """Call ``fn()`` once; return its wall-clock and process-CPU time and its result."""
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        return cls(time.perf_counter() - t0, time.process_time() - c0), out


@dataclass
class FixedGridResult:
    """Eigenvalues of a fixed-grid sweep and the cost of its parts.

    V (T,) [m/s]; eigenvalues (T, n) complex [1/s] in LAPACK order; times of the state-matrix
    assembly, the eigendecompositions and the crossing detection; threads: BLAS threads used.
    """

    V: np.ndarray
    eigenvalues: np.ndarray
    assembly: Timing
    eig: Timing
    detection: Timing = field(default_factory=lambda: Timing(0.0, 0.0))
    crossings: tuple[Crossing, ...] = ()
    threads: int = 1

    @property
    def total(self) -> Timing:
        return Timing(self.assembly.wall + self.eig.wall + self.detection.wall,
                      self.assembly.cpu + self.eig.cpu + self.detection.cpu)


def fixed_grid_sweep(state_matrix: Callable[[np.ndarray], np.ndarray], speeds=THESIS_SPEEDS, *,
                     threads: int = 1, chunk: int = 25, vectors: bool = True,
                     detect: bool = True) -> FixedGridResult:
    """The thesis's method (§5.2.1): a full eigendecomposition of A(V) at every speed.

    ``state_matrix(V)`` is vectorised over speeds [m/s]; it is evaluated in chunks of
    ``chunk`` speeds (memory), each followed by ``numpy.linalg.eig`` of the chunk (eigenvectors
    computed when ``vectors``, as the thesis's MAC ordering needs them, then dropped).  BLAS is
    limited to ``threads`` threads.  With ``detect`` the crossings are found by
    :func:`detect_crossings` (timed separately).
    """
    V = v.increasing("speeds", speeds, "m/s")
    v.integer_at_least("threads", threads, 1)
    v.integer_at_least("chunk", chunk, 1)
    lam_parts = []
    t_asm = Timing(0.0, 0.0)
    t_eig = Timing(0.0, 0.0)
    with threadpool_limits(limits=threads):
        for i in range(0, V.size, chunk):
            Vc = V[i:i + chunk]
            ta, A = Timing.measure(lambda: state_matrix(Vc))
            if vectors:
                te, (w, _X) = Timing.measure(lambda: np.linalg.eig(A))
            else:
                te, w = Timing.measure(lambda: np.linalg.eigvals(A))
            lam_parts.append(np.asarray(w, dtype=complex))
            t_asm = Timing(t_asm.wall + ta.wall, t_asm.cpu + ta.cpu)
            t_eig = Timing(t_eig.wall + te.wall, t_eig.cpu + te.cpu)
    lam = np.concatenate(lam_parts)
    res = FixedGridResult(V, lam, t_asm, t_eig, threads=threads)
    if detect:
        res.detection, res.crossings = Timing.measure(lambda: detect_crossings(V, lam))
    return res


def _match_eigenvalues(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """perm with b[perm[i]] the continuation of a[i] (optimal assignment on |λ_a − λ_b|)."""
    cost = np.abs(a[:, None] - b[None, :])
    _, perm = linear_sum_assignment(cost)
    return perm


def _det_sign(lam: np.ndarray) -> int:
    """sign(det A) = (−1)^(number of negative real eigenvalues); complex pairs contribute +."""
    return -1 if np.count_nonzero((lam.imag == 0) & (lam.real < 0)) % 2 else 1


def detect_crossings(V: np.ndarray, lam: np.ndarray) -> tuple[Crossing, ...]:
    """Sign changes of Re λ between consecutive speeds of a fixed grid (the thesis's detection).

    Eigenvalues are followed from one speed to the next by an optimal assignment on their
    distance (on a 1 m/s grid they move little compared with their separations); every matched
    pair whose real part changes sign (Re λ = 0 counts as stable, like
    :func:`count_unstable`) is a crossing, reported once per complex-conjugate pair
    (by its Im > 0 member).  Kind: flutter if the root is complex at both ends, divergence if
    real at both ends; a root complex at one end only is a divergence when sign(det A) flips in
    the interval (a real root went through zero), otherwise flutter.  Frequency-zero events
    are intervals where the number of unstable complex roots falls by two while the number of
    unstable real roots rises by two (an unstable pair turns into two real roots).
    ``V`` (T,) [m/s], ``lam`` (T, n).
    """
    V = np.asarray(V, dtype=float)
    lam = np.asarray(lam, dtype=complex)
    out: list[Crossing] = []
    for t in range(V.size - 1):
        a, b = lam[t], lam[t + 1]
        perm = _match_eigenvalues(a, b)
        bb = b[perm]
        flips = np.nonzero((a.real > 0) != (bb.real > 0))[0]   # Re λ = 0 counts as stable
        for i in flips:
            la, lb = a[i], bb[i]
            onset = lb.real > la.real
            hot = lb if onset else la                  # the unstable end
            ca, cb = la.imag != 0, lb.imag != 0
            if ca and cb:
                kind = "flutter"
            elif not (ca or cb):
                kind = "divergence"
            else:
                kind = "divergence" if _det_sign(a) != _det_sign(b) else "flutter"
            if kind == "flutter" and (hot.imag < 0 or (hot.imag == 0 and min(la.imag, lb.imag) < 0)):
                continue                               # the conjugate of a reported root
            s = la.real / (la.real - lb.real)
            Vc = float(V[t] + s * (V[t + 1] - V[t]))
            f = 0.0 if kind == "divergence" else float(
                abs(la.imag + s * (lb.imag - la.imag)) / (2 * np.pi))
            out.append(Crossing(kind, "onset" if onset else "recovery", Vc, f,
                                (float(V[t]), float(V[t + 1]))))
        ua = ((a.real > 0) & (a.imag != 0)).sum(), ((a.real > 0) & (a.imag == 0)).sum()
        ub = ((b.real > 0) & (b.imag != 0)).sum(), ((b.real > 0) & (b.imag == 0)).sum()
        if ub[0] == ua[0] - 2 and ub[1] == ua[1] + 2:
            out.append(Crossing("divergence", "frequency-zero", float(V[t + 1]), 0.0,
                                (float(V[t]), float(V[t + 1]))))
    return tuple(out)


def count_unstable(A: np.ndarray, complex_only: bool = False) -> np.ndarray:
    """Number of eigenvalues with Re λ > 0 of each matrix of a stack (full ``eigvals``).

    ``complex_only``: count only those with Im λ ≠ 0 (a frequency-zero event changes it).
    """
    w = np.linalg.eigvals(np.asarray(A))
    unstable = w.real > 0
    if complex_only:
        unstable &= w.imag != 0
    return unstable.sum(axis=-1)


def converge_crossing(state_matrix: Callable[[np.ndarray], np.ndarray], lo: float, hi: float,
                      *, xtol: float = 1e-4, complex_only: bool = False) -> tuple[float, float]:
    """Converged location of a crossing in [lo, hi] [m/s] by brute-force bisection.

    Each step evaluates A(V) and its full ``eigvals`` and halves the bracket on whether the
    number of eigenvalues with Re λ > 0 (:func:`count_unstable`; ``complex_only`` for a
    frequency-zero event) equals its value at ``lo``.  Needs the count to differ at the ends;
    with a single event inside the bracket the result is within ``xtol``/2 of it.  Returns
    (V, half-width) [m/s].
    """
    lo, hi = float(v.finite("lo", lo, "m/s")), float(v.finite("hi", hi, "m/s"))
    if not hi > lo:
        raise v.InputError(f"bracket ({lo!r}, {hi!r}) m/s is invalid: must have hi > lo")
    v.positive("xtol", xtol, "m/s")
    with threadpool_limits(limits=1):
        n_lo, n_hi = count_unstable(state_matrix(np.array([lo, hi])), complex_only)
        if n_lo == n_hi:
            raise v.InputError(f"no change of the unstable-root count between {lo} and {hi} m/s "
                               f"({n_lo} at both ends): not a single crossing")
        while hi - lo > xtol:
            mid = 0.5 * (lo + hi)
            n_mid = count_unstable(state_matrix(np.array([mid])), complex_only)[0]
            if n_mid == n_lo:
                lo = mid
            else:
                hi = mid
    return 0.5 * (lo + hi), 0.5 * (hi - lo)


def engine_crossings(analysis) -> tuple[Crossing, ...]:
    """Crossings of a :class:`propwhirl.analysis.stability.ModelAnalysis`: onsets, recoveries and
    frequency-zero events (``unstable-at-start`` is not a crossing and is left out)."""
    bracket = {(p.mode, float(p.V)): tuple(map(float, p.bracket))
               for p in analysis.criticals.points}
    return tuple(Crossing(e.kind, e.event, float(e.V), float(e.frequency_hz),
                          bracket.get((e.mode, float(e.V)), (float(e.V), float(e.V))), e.label)
                 for e in analysis.events if e.event != "unstable-at-start")


def match_crossings(found: Sequence[Crossing], reference: Sequence[Crossing], *,
                    dV: float = 1.0, df_abs: float = 0.05, df_rel: float = 0.02
                    ) -> tuple[list[tuple[Crossing, Crossing]], list[Crossing], list[Crossing]]:
    """One-to-one matching of two crossing lists: same event and kind, |ΔV| ≤ dV [m/s],
    |Δf| ≤ df_abs [Hz] + df_rel·f.  Returns (pairs, unmatched found, unmatched reference);
    the assignment minimises Σ|ΔV| (optimal, not greedy)."""
    nf, nr = len(found), len(reference)
    if nf == 0 or nr == 0:
        return [], list(found), list(reference)
    big = 1e9
    cost = np.full((nf, nr), big)
    for i, a in enumerate(found):
        for j, b in enumerate(reference):
            ok = (a.event == b.event and a.kind == b.kind and abs(a.V - b.V) <= dV
                  and abs(a.frequency_hz - b.frequency_hz)
                  <= df_abs + df_rel * max(a.frequency_hz, b.frequency_hz))
            if ok:
                cost[i, j] = abs(a.V - b.V)
    rows, cols = linear_sum_assignment(cost)
    pairs = [(found[i], reference[j]) for i, j in zip(rows, cols) if cost[i, j] < big]
    used_f = {i for i, j in zip(rows, cols) if cost[i, j] < big}
    used_r = {j for i, j in zip(rows, cols) if cost[i, j] < big}
    return (pairs, [c for i, c in enumerate(found) if i not in used_f],
            [c for j, c in enumerate(reference) if j not in used_r])
