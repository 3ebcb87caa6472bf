"""Whether compressibility moves an analysis's results: a Mach warning derived from the case
(issue 37, item 5).

The incompressible strips are flagged above Mach 0.7 by
:func:`propwhirl.model.aerodynamics.validity.analysis_warnings`; below it compressibility can
still move an event by far more than the analysis's accuracy (the wingtip model's 6 Hz whirl:
docs/validation.md, "Why the 6 Hz whirl drops").  So each event of a wing with incompressible
strip aerodynamics is recomputed on its Prandtl–Glauert twin (the same model with
``compressibility = "prandtl-glauert"``, Mach V/a at each speed,
:mod:`propwhirl.model.aerodynamics.compressibility`), locally, from the event's own root:

* an onset or recovery (a crossing with its eigenvector): the twin's root continued from it by
  shifted inverse iteration on the full-order sparse pencil
  (:func:`propwhirl.engine.correction.full_order_root`), its crossing by the secant method
  on Re λ(V) (at most :data:`MAX_STEPS` pencils); the warning when it moves by
  :data:`SHIFT_WARN` or more of the speed, naming the event, its Mach number, the twin's speed
  and the option;
* a near-neutral hump: a mode whose damping g = 2 Re λ / |Im λ| has an interior maximum along
  the speeds within :data:`HUMP_G` of zero without crossing — the twin's root at that speed,
  and the warning when it is unstable there or its g has moved by half of |g| or more (either
  way: a mode this near instability whose damping moves that much with Mach is not known to
  the strips' accuracy).

A p-k analysis (``method="pk"``) has its onsets and recoveries recomputed by the p-k itself on
the twin (:func:`pk_warnings`).

Cost: one sparse factorisation per pencil, a few pencils per event (no second analysis).  Not
checked (already compressible, or no root to start from): a
doublet-lattice wing, a wing with ``compressibility = "prandtl-glauert"``, modal models,
"unstable-at-start" and "frequency-zero" events, speeds beyond the twin's Mach 0.9 (the Mach 0.7
warning covers them).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from propwhirl import validate as v
from propwhirl.analysis.pk_iteration import pk_root
from propwhirl.engine.correction import full_order_root, real_direction
from propwhirl.model.aerodynamics import compressibility as pg
from propwhirl.model.aerodynamics.validity import MACH_COMPRESSIBLE
from propwhirl.model.frequency_domain import Galerkin, dry_assembly, pk_system

#: relative move of an event's speed [-] from which the warning is given (2 %: beyond the
#: crossing's accuracy, within the 3 % to which the thesis's speeds are reproduced)
SHIFT_WARN = 0.02
#: a near-neutral hump: largest g along the speeds in (−HUMP_G, 0)
HUMP_G = 0.01
#: most pencils per event (the secant's steps)
MAX_STEPS = 6
#: largest secant step [fraction of the speed]: the root is followed, not jumped over
STEP_MAX = 0.04
#: relative step of the first secant point without a slope [-]
FIRST_STEP = 0.01
#: the secant stops when its step is below this fraction of the speed (0.1 %: the secant converges
#: faster than linearly, so its last point is far closer; the warning states the move to 0.1 %)
VTOL = 1e-3
#: events whose Mach raises the lift slope by less than SHIFT_WARN are not recomputed (their
#: speed moves by less unless it is more than proportionally sensitive to the slope: a
#: divergence speed moves by about half the slope's change, V_D ∝ C_lα^(−1/2))
MACH_FLOOR = float(np.sqrt(1.0 - 1.0 / (1.0 + SHIFT_WARN) ** 2))


def applies(model) -> bool:
    """Whether ``model``'s events are checked: a wing model with a full-order pencil and
    incompressible strip aerodynamics on."""
    wing = getattr(model, "wing", None)
    return (hasattr(model, "second_order_blocks") and wing is not None
            and bool(getattr(model, "wing_aero", False)) and wing.aero == "strip"
            and not pg.is_compressible(wing))


def twin(model):
    """``model`` with Prandtl–Glauert strips at Mach V/a of each speed."""
    return model.with_(wing=replace(model.wing, compressibility=pg.PRANDTL_GLAUERT,
                                    strip_mach=pg.MATCHED))


def twin_assembly(model, assembly=None):
    """The assembly of :func:`twin` (``model``'s own ``assembly`` with the twin as its model
    when given: the structure, the propellers' constants and the DOFs do not depend on the
    strips' compressibility, so nothing is assembled again)."""
    comp = twin(model)
    if assembly is not None and getattr(assembly, "model", None) is model:
        return replace(assembly, model=comp)
    return comp.assembly()


def _root(model, V: float, lam: complex, x: np.ndarray):
    """The root of the pencil of ``model`` (a model or its assembly) at V [m/s] nearest λ,
    from x (None: not converged or a speed beyond the twin's Mach)."""
    try:
        F, E = model.second_order_blocks(np.array([V])).pencil(0)
    except v.InputError:                 # a matched Mach beyond the Prandtl–Glauert limit
        return None
    return full_order_root(F, E, lam, x)


def crossing(model, V0: float, lam0: complex, x0: np.ndarray, top: float,
             slope: float | None = None, direction: int = 0, root=None) -> float | None:
    """The speed [m/s] where ``model``'s root continued from (V0, λ0, x0) crosses Re λ = 0:
    Newton's first step with ``slope`` (d Re λ/dV [1/m] of the original root, e.g. the
    sweep's; without it a step of :data:`FIRST_STEP`), then the secant method, each step at
    most :data:`STEP_MAX` of the speed, to :data:`VTOL` of the speed; the crossing confirmed by
    roots on both sides of it (a hump that touches zero without crossing has none: one more
    pencil beyond the last point when the secant did not straddle it) in ``direction`` (+1:
    Re λ rising with V, an onset; −1: a recovery; 0: either).  None when a root is lost, the
    speed leaves (0, ``top``], :data:`MAX_STEPS` pencils do not converge it or it is not
    confirmed.  ``root``: (V, λ, x) ↦ (λ, x) or None, the root at V continued from (λ, x)
    (default: the full-order pencil's, :func:`_root`; a p-k analysis's: the p-k root,
    :func:`pk_warnings`)."""
    if root is None:
        def root(V, lam, x):
            return _root(model, V, lam, x)
    got = root(V0, lam0, x0)
    if got is None:
        return None
    lam, x = got
    Va, sa = V0, lam.real
    if slope is not None and np.isfinite(slope) and slope != 0.0:
        step = -sa / slope
    else:
        step = V0 * (-FIRST_STEP if sa > 0 else FIRST_STEP)
    Vb = V0 + float(np.clip(step, -STEP_MAX * V0, STEP_MAX * V0))
    points = [(Va, sa)]
    for _ in range(MAX_STEPS - 1):
        if not 0.0 < Vb <= top:
            return None
        got = root(Vb, lam, x)
        if got is None:
            return None
        lam, x = got
        sb = lam.real
        points.append((Vb, sb))
        if abs(Vb - Va) <= VTOL * Vb or sb == 0.0:
            return Vb if _confirmed(root, points, lam, x, direction, top) else None
        if sb == sa:
            return None
        step = -sb * (Vb - Va) / (sb - sa)
        step = float(np.clip(step, -STEP_MAX * Vb, STEP_MAX * Vb))   # the root may bend
        Va, sa, Vb = Vb, sb, Vb + step
    return None


def _confirmed(root, points, lam, x, direction: int, top: float) -> bool:
    """Whether the secant's ``points`` (V, Re λ), converged at the last, cross zero there in
    ``direction``: the nearest point on the other side of the last (one more pencil, a
    :data:`VTOL` step beyond, when none is), with Re λ rising (+1) or falling (−1)."""
    Vb, sb = points[-1]
    other = [(V, s) for V, s in points[:-1] if s * sb < 0]
    if not other:
        Va, sa = points[-2]
        away = np.sign(Vb - Va) if sa * sb > 0 and abs(sb) < abs(sa) else -np.sign(Vb - Va)
        Vc = Vb + away * VTOL * Vb
        if not 0.0 < Vc <= top:
            return False
        got = root(Vc, lam, x)
        if got is None or got[0].real * sb >= 0:
            return False
        other = [(Vc, got[0].real)]
    Vo, so = min(other, key=lambda p: abs(p[0] - Vb))
    rising = (sb - so) / (Vb - Vo)
    return direction * rising >= 0


def _slope(sweep, mode: int, V: float) -> float | None:
    """d Re λ/dV [1/m] of tracked ``mode`` at the sweep's speed nearest V (None without)."""
    d = getattr(sweep, "dlam_dV", None)
    if d is None or not 0 <= mode < d.shape[1]:
        return None
    return float(d[int(np.argmin(np.abs(sweep.V - V))), mode].real)


def _event_line(e, Vc: float | None, a: float) -> str | None:
    """The warning of event ``e`` (an :class:`Instability`) whose crossing with compressible
    strips is at ``Vc`` [m/s] (None: not found near it), or None when it moves by less than
    :data:`SHIFT_WARN`."""
    M = e.V / a
    factor = float(1.0 / pg.beta(M))
    head = (f"V = {e.V:.2f} m/s ({e.kind} {e.event} of {e.label}) is Mach {M:.2f}, where "
            f"compressibility raises the strips' lift slope by {100 * (factor - 1):.0f} % "
            "(Prandtl-Glauert)")
    if Vc is None:
        if factor - 1 >= 2 * SHIFT_WARN and M <= MACH_COMPRESSIBLE:   # else flagged already
            return (f"{head}; with compressible strips this crossing was not found near it "
                    "(it may move far, or a hump close): analyse with the wing's "
                    "compressibility = \"prandtl-glauert\"")
        return None
    shift = Vc / e.V - 1
    if abs(shift) < SHIFT_WARN:
        return None
    side = "unconservative" if Vc < e.V else "conservative"
    return (f"{head}: with compressible strips it is at {Vc:.2f} m/s ({100 * shift:+.1f} %; "
            f"the incompressible strips are {side} here); set the wing's compressibility = "
            "\"prandtl-glauert\"")


def _checked(e, a: float) -> bool:
    """Whether event ``e`` is recomputed: an onset or recovery at a Mach in
    [:data:`MACH_FLOOR`, the twin's :data:`~propwhirl.model.aerodynamics.compressibility.MACH_MAX`]."""
    return e.event in ("onset", "recovery") and MACH_FLOOR <= e.V / a <= pg.MACH_MAX


def event_warnings(model, events, points, top: float, comp, sweep=None) -> list[str]:
    """Warnings for the onsets and recoveries ``events`` (:class:`Instability`) whose crossing
    ``points`` (the engine's, with eigenvectors) move by :data:`SHIFT_WARN` or more on the
    Prandtl–Glauert twin of ``model`` (``comp``: :func:`twin_assembly`; ``sweep``: its slopes
    for Newton's first step)."""
    a = float(model.flight.speed_of_sound)
    out = []
    for e in events:
        if not _checked(e, a):
            continue
        p = next((q for q in points if q.mode == e.mode
                  and abs(q.V - e.V) <= 1e-9 * max(1.0, abs(e.V))), None)
        if p is None or p.eigenvector is None:
            continue
        real = e.kind == "divergence"
        x0 = real_direction(p.eigenvector) if real else np.asarray(p.eigenvector, complex)
        lam0 = p.eigenvalue.real if real else p.eigenvalue
        Vc = crossing(comp, float(p.V), lam0, x0, min(top, pg.MACH_MAX * a),
                      None if sweep is None else _slope(sweep, e.mode, e.V),
                      1 if e.event == "onset" else -1)
        line = _event_line(e, Vc, a)
        if line is not None:
            out.append(line)
    return out


def pk_warnings(model, events, top: float, basis: Galerkin | None = None) -> tuple[str, ...]:
    """:func:`event_warnings` of a p-k analysis (``analyse(method="pk")``): each onset and
    recovery's crossing on the twin by :func:`crossing` on the twin's p-k roots
    (:func:`propwhirl.analysis.pk_iteration.pk_root`, each from the last; the first at the event's
    speed from its frequency), confirmed in the event's direction: the secant to
    :data:`VTOL`, as the default's (was Brent's method to 0.01 m/s in a bracket widened
    around the event: ~3 times the p-k roots for a warning stated to 0.1 %).  ``basis``: the
    p-k sweep's Galerkin basis of ``model`` (:func:`~propwhirl.analysis.pk_basis.pk_basis`,
    where the sweep kept it), the twin's roots then on it — its static correction is the
    twin's too, the twin's steady strip loads being the model's times one factor 1/β — else
    on the twin's DOFs."""
    if not applies(model):
        return ()
    a = float(model.flight.speed_of_sound)
    comp = twin(model)
    dry = dry_assembly(comp)             # its structure and propellers, assembled once
    on = None if basis is None else Galerkin(comp, basis.Phi)
    hi = min(top, pg.MACH_MAX * a)
    out = []
    for e in events:
        if not _checked(e, a) or e.V > hi:
            continue
        omega = 2 * np.pi * e.frequency_hz
        Vc = crossing(comp, e.V, complex(0.0, omega) if omega > 0 else 0j, None, hi,
                      direction=1 if e.event == "onset" else -1,
                      root=lambda V, p, x: _pk_root(comp, V, p, dry, on))
        line = _event_line(e, Vc, a)
        if line is not None:
            out.append(line)
    return tuple(out)


def _pk_root(model, V: float, p0: complex, dry=None, basis: Galerkin | None = None):
    """(the p-k root of ``model`` at V [m/s] from ``p0``, None), or None where the k iteration
    does not converge or V is beyond the twin's Mach (``dry``: the model's
    :func:`~propwhirl.model.frequency_domain.dry_assembly`; ``basis``: on that Galerkin
    basis)."""
    try:
        system = None if basis is None else pk_system(model, V, basis=basis, dry=dry)
        return pk_root(model, V, p0, dry=dry, system=system)[0], None
    except (RuntimeError, v.InputError):
        return None


def hump_warnings(model, sweep, events, top: float, comp) -> list[str]:
    """Warnings for the near-neutral humps of ``sweep``'s oscillatory modes (interior maxima
    of g in (−:data:`HUMP_G`, 0), no event of that mode at the hump) that the
    Prandtl–Glauert twin makes unstable or whose g it moves by half of |g| or more."""
    if sweep.eigenvectors is None or sweep.V.size < 3:
        return []
    a = float(model.flight.speed_of_sound)
    lam = sweep.eigenvalues
    with np.errstate(divide="ignore", invalid="ignore"):
        g = np.where(sweep.physical & (np.abs(lam.imag) > 0), 2 * lam.real / np.abs(lam.imag),
                     np.nan)
    out = []
    for k in range(lam.shape[1]):
        gk = g[:, k]
        inner = np.flatnonzero((gk[1:-1] >= gk[:-2]) & (gk[1:-1] >= gk[2:])
                               & (gk[1:-1] < 0) & (gk[1:-1] > -HUMP_G)) + 1
        for i in inner[:1]:                       # the first hump of each mode
            V = float(sweep.V[i])
            if not MACH_FLOOR <= V / a <= pg.MACH_MAX or V > top or any(
                    e.mode == k and abs(e.V - V) <= 0.05 * V for e in events):
                continue
            got = _root(comp, V, complex(lam[i, k]), np.asarray(sweep.eigenvectors[i, :, k]))
            if got is None:
                continue
            gc = 2 * got[0].real / abs(got[0].imag)
            if gc >= 0 or abs(gc - gk[i]) >= 0.5 * abs(gk[i]):
                what = ("unstable there" if gc >= 0 else "nearer instability" if gc > gk[i]
                        else "further from instability (the incompressible strips are "
                        "conservative here)")
                out.append(
                    f"mode {sweep.mode_labels[k]} comes within g = {gk[i]:.4f} of instability "
                    f"at V = {V:.2f} m/s (Mach {V / a:.2f}) without crossing; with compressible "
                    f"strips (Prandtl-Glauert) its g there is {gc:+.4f}, {what}: set the "
                    "wing's compressibility = \"prandtl-glauert\"")
    return out


def warnings(model, events, points, sweep, assembly=None) -> tuple[str, ...]:
    """The compressibility warnings of an analysis of ``model`` (nothing when
    :func:`applies` is False): :func:`event_warnings`, then :func:`hump_warnings`;
    ``assembly``: the analysis's own assembly of ``model``, reused for the twin."""
    if not applies(model):
        return ()
    top = float(sweep.V[-1])
    comp = twin_assembly(model, assembly)
    return tuple(event_warnings(model, events, points, top, comp, sweep)
                 + hump_warnings(model, sweep, events, top, comp))
