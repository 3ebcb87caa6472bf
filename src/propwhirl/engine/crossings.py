"""All critical-point refinement: crossings of Re λ = 0, branch points, frequency-zero events.

:func:`critical_points`
    Every sign change of a tracked mode's real part, refined to ``xtol`` (default
    :data:`XTOL`) with eigenvalue-only evaluations, all crossings batched into one
    ``state_matrix`` call per round: shifted inverse iteration at the predicted eigenvalue (one
    LU factorisation and a few triangular solves instead of a full eigendecomposition); two
    evaluations at the predicted root ± 0.45 xtol, then a Newton step on their local slope
    evaluated with its two neighbours, which usually closes the bracket in two rounds
    (:class:`_RootBracket`, :class:`_Crossing`).  Classified as flutter (complex pair) or
    divergence (real root through zero: the real eigenvalue nearest zero, its sign checked
    against sign det A, so whichever root crosses is found even where a pair split inside the
    step); onsets and recoveries; hump modes; benignity (eq. 5.13) from
    dλ/dV = yᴴA'x/(yᴴx) at the crossing; the critical (lowest onset) instability.
:func:`branch_point_speeds`
    Called by the sweep loop: an unstable pair turning real (the thesis's "whirl divergence")
    is bracketed by two nodes 0.9·``min_step`` apart around its branch point (root of the
    pair's discriminant, from the 2×2 Ritz matrix of a real subspace iteration,
    :func:`propwhirl.engine.eigensolve.pair_discriminant`).
:func:`frequency_zero_points`
    The same events located to ``xtol`` by bisection on exact eigenvalue counts (the number of
    unstable complex pairs, full ``eigvals``) between the sweep's samples.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from propwhirl.engine.eigensolve import (StateMatrixFn, call_state_matrix,
                                         eigenvalue_derivative, eval_mode, pair_discriminant,
                                         single_thread_blas, zero_root)
from propwhirl.engine.hermite import hermite_coeffs, hermite_eval
from propwhirl.engine.linking import Link
from propwhirl.engine.nodes import Node
from propwhirl.engine.options import TrackingOptions
from propwhirl.engine.results import CriticalPoint, Criticals, FrequencyZero, Hump, Sweep
from propwhirl.validate import InputError, positive

#: Default width [m/s] to which critical speeds are refined (:func:`critical_points`,
#: :func:`frequency_zero_points`, :func:`propwhirl.engine.analyse`,
#: :func:`propwhirl.analysis.analyse`): 0.01 m/s, the last digit the thesis prints.
XTOL = 0.01


@dataclass
class _Bracket:
    """Hermite model of one tracked mode between two sweep samples."""

    Va: float
    Vb: float
    coeffs: tuple            # complex Hermite coefficients in s = (V − Va)/(Vb − Va)
    xa: np.ndarray
    xb: np.ndarray

    def predict(self, V: float) -> complex:
        s = (V - self.Va) / (self.Vb - self.Va)
        return complex(hermite_eval(self.coeffs, s))

    def shape(self, V: float) -> np.ndarray:
        s = float(np.clip((V - self.Va) / (self.Vb - self.Va), 0.0, 1.0))
        x = (1 - s) * self.xa + s * self.xb
        return x / np.linalg.norm(x)


class _RootBracket:
    """Safeguarded root bracketing by rounds of two evaluations (one batched model call).

    Each round evaluates f at the current prediction ± δ (δ = 0.45 × the target width): if
    the root lies between them the bracket closes at once (width 0.9 × target); otherwise
    their secant — a local slope — gives a Newton step for the next prediction, with a
    bisection when that leaves the bracket or the bracket stops halving.  ``f`` values that
    carry only a sign (``valid`` False) update the bracket but give no slope.
    """

    def __init__(self, lo: float, hi: float, flo: float, fhi: float, guess: float,
                 width: float, centre: bool = False):
        self.lo, self.hi, self.flo, self.fhi = lo, hi, flo, fhi
        self.guess, self.width, self.stall = guess, width, 0
        self.centre, self.rounds = centre, 0

    @property
    def closed(self) -> bool:
        return self.hi - self.lo <= self.width

    def proposals(self) -> list[float]:
        """g ± δ; with ``centre``, after the first round also g itself (a Newton prediction
        from a local slope is usually that accurate, and then g is the root's evaluation)."""
        d = 0.45 * self.width
        c = float(np.clip(self.guess, self.lo + d, self.hi - d))
        return [c - d, c, c + d] if self.centre and self.rounds else [c - d, c + d]

    def feed(self, values: dict[float, tuple[float, bool]]) -> None:
        width = self.hi - self.lo
        self.rounds += 1
        for V in sorted(values):
            f = values[V][0]
            if not self.lo < V < self.hi:
                continue
            if f == 0.0:
                self.lo = self.hi = V
                self.flo = self.fhi = 0.0
                return
            if np.sign(f) == np.sign(self.flo):
                self.lo, self.flo = V, f
            else:
                self.hi, self.fhi = V, f
        if self.closed:
            return
        pts = sorted(values.items())
        (u1, (f1, ok1)), (u2, (f2, ok2)) = pts[0], pts[-1]
        self.stall = self.stall + 1 if self.hi - self.lo > 0.5 * width else 0
        r = np.nan
        if ok1 and ok2 and f1 != f2:
            r = 0.5 * (u1 + u2) - 0.5 * (f1 + f2) * (u2 - u1) / (f2 - f1)
        if self.stall >= 2 or not (self.lo < r < self.hi):
            r = 0.5 * (self.lo + self.hi)
            self.stall = 0
        self.guess = float(r)

    def interpolate(self) -> float:
        """The root by linear interpolation inside the bracket."""
        if self.fhi == self.flo:
            return 0.5 * (self.lo + self.hi)
        return self.lo - self.flo * (self.hi - self.lo) / (self.fhi - self.flo)


class _BranchPoint:
    """Location of the branch point inside a step where a pair turns into two real roots.

    Root of the pair's discriminant D(V) (:func:`pair_discriminant`), analytic and with a
    simple zero there; started from its cubic Hermite model (D = ((λ1 − λ2)/2)²,
    D' = (λ1 − λ2)(λ1' − λ2')/2 at both samples), bracketed to ``width`` by
    :class:`_RootBracket`.
    """

    def __init__(self, a: Node, b: Node, i: int, ic: int, j: int, jc: int, width: float):
        h = b.V - a.V
        da = ((a.lam[i] - a.lam[ic]) / 2) ** 2
        db = ((b.lam[j] - b.lam[jc]) / 2) ** 2
        ga = (a.lam[i] - a.lam[ic]) * (a.dlam[i] - a.dlam[ic]) / 2
        gb = (b.lam[j] - b.lam[jc]) * (b.dlam[j] - b.dlam[jc]) / 2
        c = tuple(np.real(x) for x in hermite_coeffs(da, db, ga, gb, h))
        roots = np.roots([c[3], c[2], c[1], c[0]]) if any(ci != 0 for ci in c[1:]) else []
        roots = [r.real for r in np.atleast_1d(roots) if abs(r.imag) < 1e-12 and 0 < r.real < 1]
        fa, fb = float(np.real(da)), float(np.real(db))
        s0 = roots[0] if roots else (fa / (fa - fb) if fa != fb else 0.5)
        self.mean = tuple(np.real(x) for x in hermite_coeffs(
            0.5 * (a.lam[i] + a.lam[ic]), 0.5 * (b.lam[j] + b.lam[jc]),
            0.5 * (a.dlam[i] + a.dlam[ic]), 0.5 * (b.dlam[j] + b.dlam[jc]), h))
        self.Va, self.Vb = a.V, b.V
        self.Q = {a.V: np.stack([a.X[:, i].real, a.X[:, i].imag], axis=1),
                  b.V: np.stack([b.X[:, j].real, b.X[:, jc].real], axis=1)}
        self.m: dict[float, float] = {}
        self.rb = _RootBracket(a.V, b.V, fa, fb, a.V + float(s0) * h, width)

    @classmethod
    def from_estimate(cls, a: Node, i: int, ic: int, V_est: float, sigma: float, Vb: float,
                      width: float) -> "_BranchPoint":
        """The pair (i, ic) of ``a`` turns real near V_est (double root ≈ sigma) before Vb,
        after which it need not exist any more (a member may merge with another root)."""
        self = cls.__new__(cls)
        self.mean = (sigma, 0.0, 0.0, 0.0)
        self.Va, self.Vb = a.V, Vb
        self.Q = {a.V: np.stack([a.X[:, i].real, a.X[:, i].imag], axis=1)}
        self.m = {a.V: sigma}
        fa = float(np.real(((a.lam[i] - a.lam[ic]) / 2) ** 2))
        self.rb = _RootBracket(a.V, Vb, fa, 1e-300, V_est, width)
        return self

    def evaluate(self, V: float, A: np.ndarray) -> tuple[float, bool]:
        Vn = min(self.Q, key=lambda u: abs(u - V))
        sigma = self.m.get(Vn, float(hermite_eval(self.mean, (V - self.Va) / (self.Vb - self.Va))))
        D, mean, Q, ok = pair_discriminant(A, self.Q[Vn], sigma)
        if ok:
            self.Q[V], self.m[V] = Q, mean
        return D, ok


def branch_point_speeds(fn, steps: list[tuple[Node, Node, Link]], n: int, labels,
                        opts: TrackingOptions, stats: dict[str, int]) -> list[float]:
    """Speeds bracketing each unstable pair that turns into two real roots inside a step.

    The frequency of such a mode falls to zero at the branch point (the thesis's "whirl
    divergence" of an already unstable whirl mode); two nodes 0.9·min_step apart around it
    make the V-g-f data show it where it is, and let a caller bisecting on the sweep's samples
    start from that bracket.  Pairs already bracketed that tightly are left alone.
    """
    jobs = []
    width = 0.9 * opts.min_step
    for a, b, lk in steps:
        if b.V - a.V <= opts.min_step:
            continue
        seen = set()
        for V_est, i, ic, sigma in lk.branch_points:
            jobs.append(_BranchPoint.from_estimate(a, i, ic, V_est, sigma, b.V, width))
            seen.update((i, ic))
        for i in np.nonzero((a.lam.imag > 0) & (a.lam.real > 0))[0]:
            ic = a.conj[i]
            j, jc = lk.perm[i], lk.perm[ic]
            if i not in seen and b.lam[j].imag == 0 and b.lam[jc].imag == 0 and max(
                    b.lam[j].real, b.lam[jc].real) > 0:
                jobs.append(_BranchPoint(a, b, int(i), int(ic), int(j), int(jc), width))
    pending = [job for job in jobs if not job.rb.closed]
    for _round in range(12):
        if not pending:
            break
        asks = [(job, v) for job in pending for v in job.rb.proposals()]
        speeds = np.array(sorted({v for _, v in asks}))
        A = call_state_matrix(fn, speeds, n, labels)
        stats["branch_point_evaluations"] = stats.get("branch_point_evaluations", 0) + len(asks)
        for job in pending:
            job.rb.feed({v: job.evaluate(v, A[int(np.searchsorted(speeds, v))])
                         for j2, v in asks if j2 is job})
        pending = [job for job in pending if not job.rb.closed]
    out = []
    for job in jobs:
        if job.rb.closed:
            out += [v for v in (job.rb.lo, job.rb.hi) if job.Va < v < job.Vb]
    return sorted(set(out))


class _Crossing:
    """Refinement of one sign change of Re λ of a tracked branch, by batched rounds.

    Each round asks for speeds (:meth:`requests`), the caller evaluates the state matrices of
    all crossings in one model call and feeds them back (:meth:`feed`).

    * kind "flutter" — Re λ of the tracked mode (shifted inverse iteration at the
      prediction, identity checked by MAC, full-eig fallback);
    * kind "divergence" — the real root through zero: the real eigenvalue nearest zero
      (inverse iteration at shift 0), accepted only where its sign agrees with sign det A
      (relative to the bracket's ends); elsewhere only that sign is known and the step is a
      bisection.  Exact whichever real root the branch owns (e.g. after a pair split).

    Bracketing (:class:`_RootBracket`): two evaluations at the predicted root ± 0.45 xtol;
    their sign change closes the bracket (width 0.9 xtol) at once, otherwise their secant
    gives a Newton prediction (local slope), evaluated with its neighbours ± 0.45 xtol —
    usually the root's own evaluation then, reported as the crossing — safeguarded by
    bisection.  Otherwise the crossing (linear interpolation in the final bracket) is
    evaluated in one more round.  Benignity: dλ/dV at the crossing from a forward difference
    of A (one more state matrix in the same round), or a central difference of ζ when
    ``benignity_step`` is given.
    """

    def __init__(self, res: Sweep, k: int, t0: int, t1: int, kind: str, xtol: float,
                 bstep: float | None, det_signs: np.ndarray):
        self.res, self.k, self.kind, self.xtol, self.bstep = res, k, kind, xtol, bstep
        self.t0, self.t1 = t0, t1
        la, lb = res.eigenvalues[t0, k], res.eigenvalues[t1, k]
        self.Va, self.Vb = float(res.V[t0]), float(res.V[t1])
        self.direction = "onset" if lb.real > la.real else "recovery"
        coeffs = hermite_coeffs(la, lb, res.dlam_dV[t0, k], res.dlam_dV[t1, k],
                                 self.Vb - self.Va)
        self.br = _Bracket(self.Va, self.Vb, coeffs, res.eigenvectors[t0, :, k],
                           res.eigenvectors[t1, :, k])
        self.real_root = la.imag == 0 and lb.imag == 0
        self.det_a = float(det_signs[t0])
        self.points: dict[float, tuple[float, complex, np.ndarray, bool]] = {}
        self.rb = _RootBracket(self.Va, self.Vb, float(la.real), float(lb.real),
                               self._initial_guess(res, k, t0, t1), xtol, centre=True)
        self.phase = "final" if self.rb.closed else "bracket"
        self.result: CriticalPoint | None = None

    # -- predictions ------------------------------------------------------------------------
    def _initial_guess(self, res, k, t0, t1) -> float:
        la, lb = res.eigenvalues[t0, k], res.eigenvalues[t1, k]
        f = None
        if self.kind == "divergence" and (la.imag != 0) != (lb.imag != 0):
            f = self._product_model(res, k, t0, t1)
        if f is None:
            f = tuple(np.real(c) for c in self.br.coeffs)
        c = f
        roots = np.roots([c[3], c[2], c[1], c[0]]) if any(ci != 0 for ci in c[1:]) else []
        roots = [r.real for r in np.atleast_1d(roots) if abs(r.imag) < 1e-12 and 0 <= r.real <= 1]
        s0 = roots[0] if roots else (la.real / (la.real - lb.real) if la.real != lb.real
                                     else 0.5)
        return self.Va + float(s0) * (self.Vb - self.Va)

    @staticmethod
    def _product_model(res, k, t0, t1):
        """Hermite model of the product of the pair's two roots over a split/merge step (it
        crosses zero with the real root), or None when the pair cannot be identified."""
        lam, dl = res.eigenvalues, res.dlam_dV
        tc = t0 if lam[t0, k].imag != 0 else t1
        others = np.abs(lam[tc] - np.conj(lam[tc, k]))
        others[k] = np.inf
        kp = int(np.argmin(others))
        if others[kp] > 1e-9 * max(abs(lam[tc, k]), 1e-300):
            return None
        tr = t1 if tc == t0 else t0
        if lam[tr, k].imag != 0 or lam[tr, kp].imag != 0:
            return None
        p = [lam[t, k] * lam[t, kp] for t in (t0, t1)]
        dp = [dl[t, k] * lam[t, kp] + lam[t, k] * dl[t, kp] for t in (t0, t1)]
        c = hermite_coeffs(p[0], p[1], dp[0], dp[1], res.V[t1] - res.V[t0])
        return tuple(np.real(ci) for ci in c)

    def _nearest(self, V: float):
        if not self.points:
            return None
        Vn = min(self.points, key=lambda u: abs(u - V))
        return self.points[Vn]

    def _sigma(self, V: float) -> complex:
        """Shift: linear model through the two nearest evaluations, else the Hermite model."""
        good = [(u, p[1]) for u, p in self.points.items() if p[3]]
        if len(good) >= 2:
            (u1, l1), (u2, l2) = sorted(good, key=lambda q: abs(q[0] - V))[:2]
            if u1 != u2:
                sig = l1 + (l2 - l1) * (V - u1) / (u2 - u1)
                return complex(sig.real, 0.0) if self.real_root else complex(sig)
        sig = self.br.predict(V)
        return complex(sig.real, 0.0) if self.real_root else sig

    # -- rounds -----------------------------------------------------------------------------
    @property
    def done(self) -> bool:
        return self.phase == "done"

    def _fd(self, V: float) -> float:
        return 1e-6 * max(V, 1.0)

    def requests(self) -> list[tuple[float, bool]]:
        """Speeds of this round: (V, True) for an evaluation of the mode, (V, False) for a
        state matrix only (the forward difference of dλ/dV for the benignity)."""
        if self.phase == "bracket":
            pts = self.rb.proposals()
            out = [(v, True) for v in pts]
            if self.kind == "flutter" and self.bstep is None and len(pts) == 3:
                out.append((pts[1] + self._fd(pts[1]), False))
            return out
        self.Vc = self.rb.interpolate()
        out = [(self.Vc, True)]
        if self.kind == "flutter":
            if self.bstep is None:
                out.append((self.Vc + self._fd(self.Vc), False))
            else:
                out += [(self.Vc - self.bstep, True), (self.Vc + self.bstep, True)]
        return out

    def evaluate(self, V: float, A: np.ndarray, stats: dict[str, int], final: bool = False
                 ) -> tuple[float, complex, np.ndarray, bool]:
        """(f, λ, x, f is a value rather than a sign) at speed V; ``final``: the crossing
        itself, where a divergence root that the iteration could not isolate is taken from a
        full eigendecomposition (the real eigenvalue nearest zero)."""
        near = self._nearest(V)
        if self.kind == "flutter":
            x0 = near[2] if near is not None else self.br.shape(V)
            lam, x, _ = eval_mode(A, self._sigma(V), x0, self.res.displacement, 0.5, stats)
            return float(lam.real), lam, x, True
        real_b = self.res.eigenvalues[self.t1, self.k].imag == 0
        x0 = near[2] if near is not None else (self.br.xb if real_b else self.br.xa)
        lam, x, ok, sign = zero_root(A, x0, stats)
        want = np.sign(self.rb.flo) if sign == self.det_a else np.sign(self.rb.fhi)
        if ok and (final or (np.sign(lam.real) == want and lam.real != 0)):
            return float(lam.real), lam, x, True
        if final:
            stats["fallback_eig"] = stats.get("fallback_eig", 0) + 1
            w, X = np.linalg.eig(A)
            j = int(np.argmin(np.abs(w) + np.where(w.imag == 0, 0.0, np.inf)))
            return float(w[j].real), complex(w[j]), X[:, j].astype(complex), True
        stats["sign_only"] = stats.get("sign_only", 0) + 1
        return float(want) * 1e-300, lam, x, False

    def feed(self, values: dict[float, tuple[float, complex, np.ndarray, bool]],
             mats: dict[float, np.ndarray], stats: dict[str, int]) -> None:
        self.points.update(values)
        if self.phase == "bracket":
            self.rb.feed({V: (v[0], v[3]) for V, v in values.items()})
            if not self.rb.closed:
                return
            mid = sorted(values)[1] if len(values) == 3 and self.bstep is None else None
            if mid is not None and self.rb.lo <= mid <= self.rb.hi and values[mid][3]:
                self._finish(mid, values, mats, stats)        # the Newton point is the root's
                return
            self.phase = "final"
            return
        self._finish(self.Vc, values, mats, stats)

    def _finish(self, Vc: float, values, mats, stats) -> None:
        _, lam_c, x_c, _ = values[Vc]
        if self.kind == "divergence":
            lam_c = complex(lam_c.real, 0.0) if lam_c.imag == 0 else lam_c
        if lam_c.imag < 0:
            lam_c, x_c = lam_c.conjugate(), x_c.conj()
        dz = ben = None
        if self.kind == "flutter":
            if self.bstep is None:
                h = self._fd(Vc)
                dlam = eigenvalue_derivative(mats[Vc], (mats[Vc + h] - mats[Vc]) / h, lam_c,
                                             x_c, stats)
                dz = _dzeta(lam_c, dlam)
            else:
                h = self.bstep
                dz = (_zeta(values[Vc + h][1]) - _zeta(values[Vc - h][1])) / (2 * h)
            ben = 1.0 / dz if dz != 0 else None
        res = self.res
        self.result = CriticalPoint(
            mode=self.k, label=res.mode_labels[self.k], kind=self.kind,
            direction=self.direction, V=float(Vc), bracket=(self.rb.lo, self.rb.hi),
            frequency_hz=abs(lam_c.imag) / (2 * np.pi), eigenvalue=lam_c, dzeta_dV=dz,
            benignity=ben, eigenvector=x_c)
        self.phase = "done"


def _dzeta(lam: complex, dlam: complex) -> float:
    """dζ/dV of ζ = −Re λ/|λ| (eq. 5.5) from dλ/dV."""
    m = abs(lam)
    if m == 0:
        return 0.0
    return float(-(dlam.real * m * m - lam.real * (lam.conjugate() * dlam).real) / m ** 3)


def critical_points(result: Sweep, state_matrix: StateMatrixFn, *, xtol: float = XTOL,
                    benignity_step: float | None = None, zero_tol: float = 1e-9) -> Criticals:
    """Every sign change of a tracked mode's Re λ, refined to ``xtol`` [m/s].

    Eigenvalue-only: each evaluation is a state matrix (batched over all crossings per round)
    and a shifted inverse iteration (see :class:`_Crossing`).  Flutter if Im λ ≠ 0 at the
    crossing, divergence if the root is real there.  Benignity (eq. 5.13) = (dζ/dV)⁻¹ with
    dζ/dV from dλ/dV = wᵀA'x/(wᵀx) at the crossing (A' by a forward difference of step
    1e-6·max(V, 1 m/s)); with ``benignity_step`` [m/s] given, by a central difference of ζ of
    that step instead.

    Parameters
    ----------
    result : Sweep
        A tracked sweep with eigenvectors (:func:`propwhirl.engine.sweep`).
    state_matrix : callable
        The model's ``state_matrix(V)``, as given to the sweep.
    xtol : float
        Width [m/s] of the final bracket of each crossing (default :data:`XTOL`).
    benignity_step : float, optional
        Central-difference step [m/s] of ζ for the benignity.
    zero_tol : float
        |Re λ| ≤ zero_tol·max(|λ|, floor) counts as neutral (no sign) at a sample.

    Returns
    -------
    Criticals
        The crossings sorted by V, hump modes, modes unstable at the first speed.

    Examples
    --------
    An oscillator whose damping 0.5 − 0.01 V [1/s] changes sign at V = 50 m/s, where ω = 10
    rad/s and dζ/dV = 0.01/(2ω) = 5e-4 s/m:

    >>> import numpy as np
    >>> from propwhirl.engine import critical_points, sweep
    >>> def state_matrix(V):
    ...     A = np.zeros((V.size, 2, 2))
    ...     A[:, 0, 1] = 1.0
    ...     A[:, 1, 0] = -100.0
    ...     A[:, 1, 1] = -(0.5 - 0.01 * V)
    ...     return A
    >>> sw = sweep(state_matrix, np.arange(10.0, 101.0, 10.0), n_dof=1)
    >>> (p,) = critical_points(sw, state_matrix).points
    >>> p.kind, p.direction, round(p.V, 2), round(p.frequency_hz, 4)
    ('flutter', 'onset', 50.0, 1.5915)
    >>> round(p.dzeta_dV, 6), p.bracket[1] - p.bracket[0] <= 0.01
    (-0.0005, True)
    """
    positive("xtol", xtol, "m/s")
    if benignity_step is not None:
        positive("benignity_step", benignity_step, "m/s")
    with single_thread_blas():
        return refine_crossings(result, state_matrix, xtol, benignity_step, zero_tol)


def _det_signs(lam: np.ndarray) -> np.ndarray:
    """sign det A at each sample from its eigenvalues: (−1)^(number of negative real roots)."""
    neg = np.count_nonzero((lam.imag == 0) & (lam.real < 0), axis=1)
    return np.where(neg % 2 == 1, -1.0, 1.0)


def refine_crossings(res: Sweep, fn, xtol, bstep, zero_tol) -> Criticals:
    """The work of :func:`critical_points` (same arguments: ``bstep`` its
    ``benignity_step``), its arguments checked by the caller and BLAS already at one thread:
    what the sweep loop calls."""
    if res.eigenvectors is None:
        raise InputError("critical_points needs a Sweep with eigenvectors (to start the "
                         "inverse iterations); this one was saved without them")
    stats: dict[str, int] = {}
    lam, V = res.eigenvalues, res.V
    tol = zero_tol * np.maximum(np.abs(lam), res.floor[:, None])
    sgn = np.where(np.abs(lam.real) <= tol, 0, np.sign(lam.real)).astype(int)
    dets = _det_signs(lam)
    jobs: list[_Crossing] = []
    for k in range(res.n_modes):
        idx = np.nonzero(sgn[:, k] != 0)[0]
        for t0, t1 in zip(idx[:-1], idx[1:]):
            if sgn[t0, k] == sgn[t1, k] or not res.physical[t0:t1 + 1, k].any():
                continue
            ca, cb = lam[t0, k].imag != 0, lam[t1, k].imag != 0
            if ca != cb:
                kind = "divergence" if dets[t0] != dets[t1] else "flutter"
            else:
                kind = "flutter" if ca else "divergence"
            if kind == "flutter" and not (res.physical[t0, k] and res.physical[t1, k]):
                continue                      # the hidden conjugate of a crossing pair
            jobs.append(_Crossing(res, k, int(t0), int(t1), kind, xtol, bstep, dets))
    n = res.eigenvalues.shape[1]
    pending = jobs
    while pending:
        asks = [(job, v, ev) for job in pending for v, ev in job.requests()]
        speeds = np.array(sorted({v for _, v, _ in asks}))
        A = call_state_matrix(fn, speeds, n, res.state_labels)
        stats["state_matrix_calls"] = stats.get("state_matrix_calls", 0) + 1
        for job in pending:
            final = job.phase == "final"
            mats = {v: A[int(np.searchsorted(speeds, v))] for j2, v, _ in asks if j2 is job}
            vals = {v: job.evaluate(v, mats[v], stats, final)
                    for j2, v, ev in asks if j2 is job and ev}
            stats["evaluations"] = stats.get("evaluations", 0) + len(vals)
            job.feed(vals, mats, stats)
        pending = [job for job in pending if not job.done]
    pts = sorted((job.result for job in jobs if job.result is not None), key=lambda p: p.V)
    humps = []
    for k in range(res.n_modes):
        mine = [p for p in pts if p.mode == k]
        for p, q in zip(mine[:-1], mine[1:]):
            if p.direction == "onset" and q.direction == "recovery":
                humps.append(Hump(k, p.label, p.kind, p.V, q.V))
    start = tuple(int(k) for k in np.nonzero((sgn[0] > 0) & res.physical[0])[0])
    return Criticals(tuple(pts), tuple(humps), start, stats)


def _zeta(lam: complex) -> float:
    return -lam.real / abs(lam) if lam != 0 else 0.0


def _n_unstable_pairs(state_matrix: StateMatrixFn, V: float) -> int:
    """Number of eigenvalues with Re λ > 0 and Im λ > 0 at airspeed V (a full eigvals)."""
    lam = np.linalg.eigvals(state_matrix(np.array([V]))[0])
    return int(np.sum((lam.real > 0) & (lam.imag > 1e-9 * np.maximum(1.0, np.abs(lam)))))


def frequency_zero_points(result: Sweep, state_matrix: StateMatrixFn, *,
                          xtol: float = XTOL) -> tuple[FrequencyZero, ...]:
    """Unstable oscillatory modes whose pair turns into real roots (frequency → 0).

    A physical mode that is an unstable complex pair (Re λ > 0, Im λ > 0) at one sample of
    ``result`` and an unstable real root at the next turns into two real roots in between: the
    thesis's "whirl divergence" of an already unstable whirl mode (Table 10.4).  Located by
    bisection on the number of unstable complex pairs (full eigenvalue solves: the branch
    point is a square-root singularity where a tracked single-root evaluation is
    ill-conditioned), to ``xtol`` [m/s]; the first such step of each mode, in the order of
    the mode ids.

    Parameters
    ----------
    result : Sweep
        A tracked sweep (:func:`propwhirl.engine.sweep` or ``analyse(...).sweep``).
    state_matrix : callable
        The model's ``state_matrix(V)`` (called with one speed at a time).
    xtol : float
        Width of the final bracket [m/s] (default :data:`XTOL`).

    Returns
    -------
    tuple of FrequencyZero

    Examples
    --------
    A stable oscillator and an unstable pair 1 ± √(V − 30) that turns real at V = 30 m/s:

    >>> import numpy as np
    >>> from propwhirl.engine import frequency_zero_points, sweep
    >>> def state_matrix(V):
    ...     A = np.zeros((V.size, 4, 4))
    ...     A[:, 0, 0] = A[:, 1, 1] = -0.2
    ...     A[:, 0, 1], A[:, 1, 0] = 5.0, -5.0
    ...     A[:, 2, 2] = A[:, 3, 3] = 1.0
    ...     A[:, 2, 3], A[:, 3, 2] = 1.0, V - 30.0
    ...     return A
    >>> sw = sweep(state_matrix, np.arange(1.0, 52.0, 10.0))
    >>> (p,) = frequency_zero_points(sw, state_matrix)
    >>> p.label, round(p.V, 2), p.bracket[1] - p.bracket[0] <= 0.01
    ('mode 1', 30.0, True)
    """
    positive("xtol", xtol, "m/s")
    out = []
    lam, phys = result.eigenvalues, result.physical
    with single_thread_blas():
        for k in range(result.n_modes):
            for t in range(len(result.V) - 1):
                a, b = lam[t, k], lam[t + 1, k]
                if not (phys[t, k] and a.imag > 0 and a.real > 0):
                    continue
                if abs(b.imag) > 1e-9 * max(1.0, abs(b)) or b.real <= 0:
                    continue
                lo, hi = float(result.V[t]), float(result.V[t + 1])
                n_lo = _n_unstable_pairs(state_matrix, lo)
                while hi - lo > xtol:
                    mid = 0.5 * (lo + hi)
                    if _n_unstable_pairs(state_matrix, mid) >= n_lo:
                        lo = mid
                    else:
                        hi = mid
                out.append(FrequencyZero(k, result.mode_labels[k], 0.5 * (lo + hi), (lo, hi)))
                break
    return tuple(out)
