"""How a p-k crossing (Re p = 0) is refined — one place for that decision — and the
benignity at one.

* In a bracket of the p-k sweep (:func:`bracket_crossing`,
  :func:`propwhirl.analysis.pk.pk_sweep`): the secant method from the bracket's ends' roots
  (:func:`_secant_in`), Brent's method where the secant leaves the bracket or converges onto
  a hop (:func:`_brent_between`, from the left root or the one interpolated between the
  ends'), and where Brent's met a hop onto another mode's root (:data:`HOP`, :func:`_jumps`)
  the mode continued across the bracket (:func:`_continued`).
* On the full DOFs from a crossing found on a Galerkin basis or on interpolated tables
  (:func:`full_crossing`: the secant, each speed's root from the one the bracket started
  from; a convergence onto a hop, :data:`SLOPE_JUMP`, is none), and with a Mach-matched
  doublet-lattice wing's Q at each speed's own Mach (:func:`matched_crossing`).
* Around a crossing of the default's state space (:func:`pk_crossing`, what
  :mod:`propwhirl.analysis.modal_dlm` converges a doublet-lattice wing's crossings with):
  brackets widened in turn (:data:`CROSSING_SPREAD`), a tight cluster's member followed by
  the state-space mode's shape.
* The benignity (dζ/dV)⁻¹ of the p-k root at a crossing (:func:`pk_benignity`, eq. 5.13).

Every p-k root is :func:`propwhirl.analysis.pk_iteration.pk_root`'s.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from propwhirl.analysis.pk_iteration import CLUSTER, TIGHT, XTOL, pk_root
from propwhirl.model.aerodynamics.dlm import DlmTables, check_tables, fixed_mach, strip_twin

def _brent_between(model, a: float, b: float, pa: complex, pb: complex, xtol: float,
                   tables, solve=None) -> tuple[float, complex, float]:
    """Brent's method on Re p between the speeds a < b [m/s] whose p-k roots ``pa`` and
    ``pb`` [1/s] have opposite signs of Re p, each speed's root continued from the root
    interpolated linearly between them (so that both ends are the roots the bracket was
    found with, not another mode's a far start jumps to): (V, p, k).  RuntimeError when a
    root does not converge or the ends' roots lose their signs.  ``solve``: (V, p0) ↦ (p, k),
    the root at V from p0 (default: :func:`pk_root` on the full DOFs, with ``tables``)."""
    solve = full_solver(model, tables) if solve is None else solve

    def guess(x: float) -> complex:
        return pa + (pb - pa) * (x - a) / (b - a)

    def decay(x: float) -> float:
        return solve(x, guess(x))[0].real

    try:
        V = brentq(decay, a, b, xtol=xtol)
    except ValueError:             # the ends' roots re-solved lost their signs: not a bracket
        raise RuntimeError(f"p-k bracket [{a}, {b}] m/s lost its sign change") from None
    p, k = solve(V, guess(V))
    return float(V), p, float(k)


def full_solver(model, tables, dry=None, ref=None, window: float = 0.0):
    """(V, p0) ↦ :func:`pk_root` of ``model`` on its full DOFs (``tables``: a doublet-lattice
    wing's; ``dry``: the analysis's :func:`~propwhirl.model.frequency_domain.dry_assembly`;
    ``ref``, ``window``: the root by its shape in a tight cluster)."""
    return lambda x, p0: pk_root(model, x, p0, tables=tables, dry=dry, ref=ref, window=window)


#: a crossing whose root keeps more than this fraction of the larger |Re p| of its bracket's
#: ends is no crossing but a hop: Brent's method converged onto a speed where the root
#: continued from the bracket's left end jumps to another mode's (:func:`_continued`)
HOP = 0.05
#: a crossing across which the root, continued as Brent's method did, moves by more than this
#: fraction of the mode's frequency within ±2 xtol is a hop too (:func:`_jumps`)
JUMP = 0.01


def _jumps(solve, Vf: float, bracket: tuple[float, float], ends: tuple[complex, complex],
           xtol: float, scale: float) -> bool:
    """Whether the p-k root at the crossing speed Vf [m/s] jumps: continued by ``solve``
    (V, p0) ↦ (p, k) from the ``bracket``'s [m/s] left root ``ends[0]`` and from the root
    interpolated between its ends' (both ways Brent's method may have solved it), at
    Vf ∓ 2 ``xtol`` it differs by more than :data:`JUMP` × ``scale`` [1/s] (the mode's
    in-vacuo frequency or |p|).  A true crossing is continuous there (a change of ~1e-4 of the
    frequency); Brent's method converges onto a hop as readily — the wingtip example's
    17.7 Hz mode, whose root went from the 6 Hz mode's (Re p = −0.57) to the 7 Hz mode's
    (+18.4) between two speeds, had false flutter onsets and recoveries from 160.9 to
    256.2 m/s, which the |Re p| test (:data:`HOP`, of the larger end's) passed."""
    a, b = Vf - 2 * xtol, Vf + 2 * xtol
    v0, v1 = bracket
    for guess in (lambda x: ends[0],
                  lambda x: ends[0] + (ends[1] - ends[0]) * (x - v0) / (v1 - v0)):
        try:
            lo, _ = solve(a, guess(a))
            hi, _ = solve(b, guess(b))
        except RuntimeError:
            return True
        if abs(hi - lo) > JUMP * scale:
            return True
    return False


#: speed steps :func:`_continued` continues a mode by across a bracket
CONTINUATION_STEPS = 16


def _continued(model, a: float, b: float, pa: complex, xtol: float,
               tables, solve=None) -> tuple[float, complex, float] | None:
    """The crossing (Re p = 0) of the mode whose p-k root is ``pa`` [1/s] at a [m/s],
    continued to b [m/s] in :data:`CONTINUATION_STEPS` steps, each speed's root from the one
    extrapolated from the last two (so that it stays on its own branch where other modes' roots
    lie nearer its root at a than its own: a cluster of near-identical propellers), refined by
    Brent's method to ``xtol`` on the first step whose ends' roots change sign: (V, p, k), or
    None when the continued root keeps its sign (the bracket's sign change was a hop onto
    another mode's root).  RuntimeError when a root does not converge or hops again.
    ``solve``: as :func:`_brent_between`'s."""
    solve = full_solver(model, tables) if solve is None else solve
    xs = np.linspace(a, b, CONTINUATION_STEPS + 1)
    prev, cur = complex(pa), complex(pa)
    for x0, x1 in zip(xs[:-1], xs[1:]):
        guess = 2 * cur - prev if x0 > a else cur
        nxt, _ = solve(float(x1), guess)
        if cur.real != 0 and nxt.real != 0 and (cur.real > 0) != (nxt.real > 0):
            left = cur

            def decay(x: float) -> float:
                return solve(x, left + (nxt - left) * (x - x0) / (x1 - x0))[0].real

            try:
                V = brentq(decay, float(x0), float(x1), xtol=xtol)
            except ValueError:
                raise RuntimeError(f"p-k continuation [{x0}, {x1}] m/s lost its sign "
                                   "change") from None
            p, k = solve(V, left + (nxt - left) * (V - x0) / (x1 - x0))
            if abs(p.real) > HOP * max(abs(left.real), abs(nxt.real)):
                raise RuntimeError(f"p-k root hops between {x0} and {x1} m/s")
            return float(V), p, float(k)
        prev, cur = cur, nxt
    return None


#: secant steps :func:`matched_crossing` takes at most
MATCHED_STEPS = 12
#: a secant that converges with a slope d Re p/dV over this many times the one it started
#: from converged onto a hop (:func:`full_crossing`): a root that jumps from one branch to
#: another with the opposite sign of Re p (x57_like's neighbouring propellers on panels,
#: ~1e-3 of |p| apart) draws the secant onto the jump with slopes growing without bound
#: (their two branches in tests/analysis/test_pk.py: 3.7 against 0.015 1/s per m/s, 250
#: times).  On the crossings of every case of benchmarks/pk_events_compare.py, p-k and
#: default, the ratio is 0.88-1.6.  A hop this lets pass (a jump of Re p under ~0.005 m/s ×
#: this × the slope) lies within ~0.05 m/s of its branch's true crossing
SLOPE_JUMP = 10.0


def matched_crossing(model, V0: float, p0: complex, slope: float, *, lo: float, hi: float,
                     xtol: float = XTOL, tables: DlmTables | None = None,
                     dry=None, ref=None,
                     window: float = 0.0) -> tuple[float, complex, float] | None:
    """The crossing Re p = 0 of a Mach-matched doublet-lattice wing with Q at the Mach V/a of
    every speed tried (issue 37 item 5): from the AICs of the fine columns
    (:data:`~propwhirl.model.aerodynamics.dlm.MACH_FINE` = 0.001 apart) around it, within 2e-7
    of max |Q| of that Mach's own AICs at Mach 0.6, from the crossing ``V0`` [m/s] (root
    ``p0`` [1/s]) found on the tables' Mach interpolation, whose ``slope`` d Re p/dV [1/s per
    m/s] starts the secant method: (V [m/s], p, k), V within ``xtol`` / 10 of the root (the
    last secant step: a fixed-Mach analysis at V/a moves its onset by (dV/dM)/a times that,
    ~9 on the wingtip wing's near-neutral whirl hump), or None when the secant leaves
    [``lo``, ``hi``], meets a flat Re p or takes more than :data:`MATCHED_STEPS` steps (the
    caller keeps V0).

    Between the tables' Mach nodes (0.05 apart) Q is linear in Mach, within ~5e-4 of max |Q| of
    the AICs at that Mach (Mach 0.6-0.66); a near-neutral whirl mode (a damping hump just
    touching zero) turns that into metres per second of onset.  At its own Mach, the onset
    is the one the same wing has with its ``dlm_mach`` fixed at the onset's own V/a (tested).
    ``ref``, ``window``: each root's by its shape in a tight cluster (:func:`pk_root`).
    """
    return full_crossing(model, V0, p0, slope, lo=lo, hi=hi, xtol=xtol, tables=tables,
                         own_mach=True, dry=dry, ref=ref, window=window)


def full_crossing(model, V0: float, p0: complex, slope: float, *, lo: float, hi: float,
                  xtol: float = XTOL, tables: DlmTables | None = None, own_mach: bool = False,
                  start=None, dry=None, ref=None,
                  window: float = 0.0) -> tuple[float, complex, float] | None:
    """The crossing Re p = 0 on the full DOFs of the mode whose root is near ``p0`` [1/s] at
    ``V0`` [m/s] (a crossing found on a Galerkin basis or on interpolated tables), by the secant
    method from ``slope`` d Re p/dV [1/s per m/s]: each step's p-k root from the last, until the
    step is within ``xtol`` / 10 [m/s]: (V, p, k), or None when the secant leaves [``lo``,
    ``hi``], meets a flat Re p or takes more than :data:`MATCHED_STEPS` steps.  ``own_mach``:
    a Mach-matched doublet-lattice wing's Q at each speed's own Mach (:func:`matched_crossing`).
    ``start``: V ↦ the root each speed's k iteration starts from (the one the crossing was
    bracketed with, :func:`bracket_crossing`: near a coalescence the p-k has two roots there,
    and the start decides which); None: from the previous step's root.  ``ref``, ``window``: each
    root's by its shape in a tight cluster (:func:`pk_root`).  Where the reduced crossing is
    within xtol / 10 of the full one, one p-k root decides it.  A root that hops from one
    mode's branch to another's between the last two steps makes the secant's slope steep and
    its step short without a crossing: a converged step whose slope is over :data:`SLOPE_JUMP`
    times the given ``slope`` is None."""
    def solve(x: float, q: complex) -> tuple[complex, float]:
        return pk_root(model, x, q, tables=tables, own_mach=own_mach, dry=dry, ref=ref,
                       window=window)

    try:
        return _secant(solve, float(V0), complex(p0), slope, lo=lo, hi=hi, xtol=xtol,
                       start=start)
    except RuntimeError:                      # a root that does not converge
        return None


def _secant(solve, V: float, p0: complex, slope: float, *, lo: float, hi: float, xtol: float,
            start=None, scale: float | None = None) -> tuple[float, complex, float] | None:
    """The secant method on Re p from V [m/s] with the first ``slope`` d Re p/dV, each
    speed's root by ``solve`` (V, p0) ↦ (p, k) from ``start`` (V) (None: from the previous
    step's root, the first from ``p0``), until a step is within ``xtol`` / 10 [m/s]:
    (V, p, k) — :func:`full_crossing`'s and :func:`_secant_in`'s.  None when the slope is 0
    or not finite, a step leaves [``lo``, ``hi``], :data:`MATCHED_STEPS` steps do not
    converge, or it converged onto a hop: its last slope over :data:`SLOPE_JUMP` times the
    first, or (``scale`` [1/s] given) its last two roots more than :data:`JUMP` × ``scale``
    apart.  A RuntimeError of ``solve`` is passed on."""
    if not np.isfinite(slope) or slope == 0.0:
        return None
    given, guess = slope, complex(p0)
    prev = None                                  # (V, p) of the previous point
    for _ in range(MATCHED_STEPS):
        p, k = solve(V, guess if start is None else start(V))
        if prev is not None and p.real != prev[1].real:
            slope = (p.real - prev[1].real) / (V - prev[0])     # the secant's
        step = 0.0 if p.real == 0.0 else -p.real / slope
        if abs(step) <= 0.1 * xtol:
            if abs(slope) > SLOPE_JUMP * abs(given) or (
                    scale is not None and prev is not None and abs(p - prev[1]) > JUMP * scale):
                return None                                    # a hop, not a crossing
            return float(V), p, float(k)
        if not (np.isfinite(step) and lo <= V + step <= hi):
            return None
        prev, guess, V = (V, p), p, V + step
    return None


#: half-widths of the brackets :func:`pk_crossing` tries around a finite-state crossing, as
#: fractions of its speed (the Roger fit's crossings lie within ~1 % of the p-k's)
CROSSING_SPREAD = (0.01, 0.02, 0.04, 0.08, 0.16)


@dataclass(frozen=True)
class PKCrossing:
    """A crossing converged by :func:`pk_crossing`: speed V [m/s], the p-k root p [1/s] and
    its k [-] there, and the direction ("onset": Re p − → + with V; "recovery")."""

    V: float
    p: complex
    k: float
    direction: str


def pk_crossing(model, V0: float, p0: complex, *, lo: float, hi: float,
                xtol: float = XTOL, tables: DlmTables | None = None,
                dry=None, shape: np.ndarray | None = None) -> PKCrossing | None:
    """The p-k crossing (Re p = 0) of the mode whose root is near ``p0`` [1/s] at V0 [m/s]:
    a bracket around V0 of half-width :data:`CROSSING_SPREAD` × V0 (widened in turn, within
    [``lo``, ``hi``] [m/s]) where the p-k root continued from ``p0`` changes sign, refined
    within it by the secant method from its ends' roots (:func:`full_crossing`, each speed's
    root from the one interpolated between the ends', to ``xtol`` / 10; 2-3 p-k roots where
    Brent's method took 5-6), by Brent's method to ``xtol`` [m/s] where the secant leaves
    the bracket.  ``shape``: the mode's displacement shape on the model's DOFs (n,) at V0
    (the state-space crossing's): in a tight cluster (near-identical propellers, roots within
    :data:`TIGHT` of |p0|) every root is that member's, the one of its shape where the MAC
    says so clearly (:func:`pk_root`), not the nearest — the nearest is another member's
    from one speed to the next, and Brent's method converged onto such a hop (x57_like on
    panels: "onsets" at 80.34-80.39 m/s with Re p = +0.0034 1/s, which the p-k does not
    have).  A Brent result whose |Re p| keeps :data:`HOP` of its ends' is such a hop: a
    wider bracket is tried.  None when the p-k root keeps its sign over the widest
    bracket (the p-k has no crossing there); RuntimeError when the k iteration does not
    converge.  What the default analysis of a doublet-lattice wing converges its modal Roger
    state space's crossings with (:mod:`propwhirl.analysis.modal_dlm`)."""
    tables = check_tables(tables) if strip_twin(model) is not model else None
    V0 = float(np.clip(V0, lo, hi))
    ref, window = None, 0.0
    if shape is not None:
        x = np.asarray(shape, dtype=complex)
        ref, window = np.concatenate([x, complex(p0) * x]), TIGHT * abs(p0)
    guess = {"lo": complex(p0), "hi": complex(p0)}
    for s in CROSSING_SPREAD:
        a, b = max(lo, V0 * (1 - s)), min(hi, V0 * (1 + s))
        pa, _ = pk_root(model, a, guess["lo"], tables=tables, dry=dry, ref=ref, window=window)
        pb, _ = pk_root(model, b, guess["hi"], tables=tables, dry=dry, ref=ref, window=window)
        guess["lo"], guess["hi"] = pa, pb
        if pa.real != 0 and pb.real != 0 and (pa.real > 0) != (pb.real > 0):
            def start(x: float, a=a, b=b, pa=pa, pb=pb) -> complex:
                return pa + (pb - pa) * (x - a) / (b - a)
            slope = (pb.real - pa.real) / (b - a)
            V1 = a - pa.real / slope                  # the secant from the ends' roots
            found = full_crossing(model, V1, start(V1), slope, lo=a, hi=b, xtol=xtol,
                                  tables=tables, start=start, dry=dry, ref=ref, window=window)
            if found is not None:
                V, p, k = found
            else:                         # the secant left the bracket: Brent's method
                try:
                    V, p, k = _brent_between(model, a, b, pa, pb, xtol, tables,
                                             full_solver(model, tables, dry, ref, window))
                except RuntimeError:      # continued from a, another root at b: not this
                    continue              # root's bracket (was a traceback); a wider one
                if abs(p.real) > HOP * max(abs(pa.real), abs(pb.real)):
                    continue              # Brent's method converged onto a hop
            if tables is not None and fixed_mach(getattr(model, "wing", model)) is None:
                exact = matched_crossing(model, V, p, (pb.real - pa.real) / (b - a), lo=lo,
                                         hi=hi, xtol=xtol, tables=tables, dry=dry, ref=ref,
                                         window=window)
                if exact is not None:
                    V, p, k = exact
            return PKCrossing(float(V), p, float(k), "onset" if pa.real < 0 else "recovery")
        if a <= lo and b >= hi:
            break
    return None



def bracket_crossing(model, bracket, xtol: float, tables, solve, scale: float):
    """The crossing of one mode in a bracket of the sweep, ``bracket`` = (a, b, p_a, p_b,
    Re p_a, Re p_b) (speeds [m/s], the mode's roots [1/s] there, of opposite signs of Re p),
    each root by ``solve`` (V, p0) ↦ (p, k), each speed's root continued from the left root,
    or — where the ends' roots are within :data:`CLUSTER` of |p| of each other, one branch
    moving continuously — from the root interpolated between them: first the secant method
    from the ends' roots (:func:`_secant_in`, to ``xtol`` / 10; 2-3 roots where Brent's method
    and the hop check below take ~10); where it leaves the bracket or converges onto a hop,
    Brent's method on Re p (:func:`_brent_between`) from that start, the other where the
    first fails; where Brent met a hop onto another mode's root, the mode continued across
    the bracket (:func:`_continued`; None: no crossing of its own): (V, p, k, start),
    ``start`` V ↦ the root each speed's iteration started from.  RuntimeError when a root does
    not converge.

    From the left root every speed's iteration starts 1-10 m/s away from its root: in
    x57_like's cluster of near-identical propellers (roots ~1e-3 of |p| apart, moving ~1 %
    per 2.5 m/s) the modes of four brackets on a 2.5 m/s grid all took the same root inside
    their brackets and converged onto one crossing (80.66 m/s), and the critical (79.99 m/s,
    the default's 80.00) was not reported; from the interpolated root each keeps its own
    (79.99, 80.07, 80.10, 80.62 and 80.66 m/s).  Where the ends are far apart the sweep's
    mode hopped onto another's root between them (the wingtip example's 17.7 Hz mode onto the
    7 Hz mode's): the interpolation would pass the hop smoothly, the left root's own branch
    shows it (:func:`_jumps`)."""
    a, b, pa, pb, sa, sb = bracket
    close = abs(pb - pa) <= CLUSTER * max(abs(pa), abs(pb))
    found = _secant_in(solve, bracket, xtol, max(scale, abs(pa)), close)
    if found is not None:
        return found

    def from_left():
        try:
            Vf = brentq(lambda x: solve(x, pa)[0].real, a, b, xtol=xtol)
        except ValueError:   # the right end, continued from the left root, is another mode's
            raise RuntimeError(f"p-k bracket [{a}, {b}] m/s: the left root's continuation "
                               "keeps its sign") from None
        return (Vf,) + solve(Vf, pa) + (lambda x: pa,)

    def between():
        return _brent_between(model, a, b, pa, pb, xtol, tables, solve) + (
            lambda x: pa + (pb - pa) * (x - a) / (b - a),)

    first, second = (between, from_left) if close else (from_left, between)
    try:
        Vf, p, k, start = first()
    except RuntimeError:
        Vf, p, k, start = second()
    if abs(p.real) > HOP * max(abs(sa), abs(sb)) or _jumps(
            solve, float(Vf), (a, b), (pa, pb), xtol, max(scale, abs(p))):
        # Brent met a hop onto another mode's root: the mode's own
        found = _continued(model, a, b, pa, xtol, tables, solve)
        return None if found is None else found + (None,)
    return float(Vf), p, float(k), start


def _secant_in(solve, bracket, xtol: float, scale: float, close: bool):
    """The crossing in a sweep's ``bracket`` (:func:`bracket_crossing`'s) by the secant method
    (:func:`_secant`) from its ends' roots, within it, each speed's root by ``solve`` from the
    root interpolated between them (``close``: one branch moving continuously) or from the
    left one: (V, p, k, start), or None where :func:`_secant` gives none (its hop test on the
    last two roots with ``scale`` [1/s], as :func:`_jumps` tests Brent's).  RuntimeError when
    a root does not converge."""
    a, b, pa, pb, sa, sb = bracket

    def start(x: float) -> complex:
        return pa + (pb - pa) * (x - a) / (b - a) if close else pa

    slope = (sb - sa) / (b - a)
    found = _secant(solve, a - sa / slope, pa, slope, lo=a, hi=b, xtol=xtol, start=start,
                    scale=scale)
    return None if found is None else found + (start,)


def at_own_mach(model, found, bracket, V, xtol: float, tables, matched: bool, dry=None):
    """``found`` (V, p, k), converged with the AICs at its own Mach on a Mach-matched
    doublet-lattice wing (:func:`matched_crossing`; kept where that fails)."""
    if not matched:
        return found
    a, b, _, _, sa, sb = bracket
    exact = matched_crossing(model, found[0], found[1], (sb - sa) / (b - a), lo=float(V[0]),
                             hi=float(V[-1]), xtol=xtol, tables=tables, dry=dry)
    return found if exact is None else exact



#: central-difference step [m/s] of the p-k damping ratio for the benignity (eq. 5.13)
BENIGNITY_STEP = 0.1


def pk_benignity(model, V: float, p: complex,
                 tables: DlmTables | None = None, dry=None) -> float | None:
    """(dζ/dV)⁻¹ [m/s] (eq. 5.13) of the p-k root through ``p`` at V, ζ = −Re p/|p| (eq. 5.5),
    by a central difference of :data:`BENIGNITY_STEP`; None if dζ/dV is 0 or a root is lost.
    On the model's DOFs: on the sweep's Galerkin basis it would be ~2 ms faster on the Goland
    wing and 0.2 % off on the wingtip wing's 4 × 12 panels (−78.49 vs −78.66 m/s, the same
    with steps of 0.05-0.2 m/s: the basis's error in the slope, not the difference's)."""
    h = BENIGNITY_STEP
    try:
        lo, _ = pk_root(model, V - h, p, tables=tables, dry=dry)
        hi, _ = pk_root(model, V + h, p, tables=tables, dry=dry)
    except RuntimeError:
        return None
    dz = (-hi.real / abs(hi) + lo.real / abs(lo)) / (2 * h)
    return 1.0 / dz if dz != 0 else None
