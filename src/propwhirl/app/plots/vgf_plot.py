"""V-g-f diagram: damping ratio ζ (eq. 5.5) and frequency [Hz] against airspeed.

By default only the modes that matter are drawn (:func:`select_modes`): those that become
unstable or come within a damping margin of it, and every mode below a frequency cut-off
(default: 1.25 × the highest frequency the modes that matter reach).  Given the model, the
curves are computed on a fine speed grid (:func:`fine_sweep`: the engine's tracked sweep over
every grid speed, named as :func:`~propwhirl.analysis.stability.analyse` names them) — the
analysis's own sweep holds only the engine's coarse nodes.  The instabilities are the
analysis's exact critical points (Figure 7.4: flutter red, divergence green; filled at an
onset, open at a recovery), each annotated with V and f.  ζ is drawn only where the root is
oscillatory (a real root has ζ = ±1 by eq. 5.5, which is no damping of a vibration: the
divergence marker shows where it crosses zero), the ζ axis limits come from the drawn data,
and the unstable half ζ < 0 is shaded.

:func:`vgf_figure` draws every V-g-f of propwhirl — an analysis's (:func:`vgf`) and a
campaign point's with its clearance requirements
(:func:`propwhirl.app.plots.campaign_plot.point_vgf`) — from the curves (:class:`VgfCurves`)
and the instabilities (:class:`VgfEvent`) each of them reads from its own data.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from propwhirl import validate as v
from propwhirl.analysis.naming import is_lag, mode_family, mode_names
from propwhirl.app.plots.canvas import (DIVERGENCE_COLOUR, FLUTTER_COLOUR, finish,
                                        matplotlib_or_error, new_figure)
from propwhirl.app.plots.layout import (FAMILY_COLOURS, family_shades, freeze_layout,
                                        place_labels, wrap, curve_boxes)
from propwhirl.engine import sweep as engine_sweep
from propwhirl.engine.hermite import hermite_coeffs, hermite_eval

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from propwhirl.analysis.stability import ModelAnalysis
    from propwhirl.engine import Sweep
    from propwhirl.model.protocol import Model

#: default damping margin: a mode whose ζ falls below it somewhere in the range is plotted
DAMPING_MARGIN = 0.03
#: default frequency cut-off: this factor × the highest frequency of the modes that matter
CUTOFF_FACTOR = 1.25
#: default number of speeds of the fine grid
FINE_SPEEDS = 101
#: label of the damping axis: the sign convention
ZETA_LABEL = "damping ratio ζ  (ζ < 0: unstable)"
#: |Im λ| / |λ| below this: a real root (no frequency; ζ not drawn)
_REAL = 1e-9


#: points of the drawn curve per analysed speed step
HERMITE_POINTS = 12


def hermite_columns(V: np.ndarray, Y: np.ndarray, dY: np.ndarray, valid: np.ndarray,
                    n: int = HERMITE_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """Each column of Y (T, m) as its cubic Hermite curve (:func:`hermite`: slopes dY [per
    m/s], straight near a branch point) on one grid of `n` points per speed step of V (T,)
    [m/s]: the grid ((T − 1) n,) and the curves ((T − 1) n, m), NaN on a step whose ends
    are not both `valid` (T, m)."""
    V = np.asarray(V, dtype=float)
    Y, dY, valid = (np.asarray(x) for x in (Y, dY, valid))
    t = np.linspace(0.0, 1.0, n)
    grid = np.concatenate([V[j] + t * (V[j + 1] - V[j]) for j in range(len(V) - 1)]) \
        if len(V) > 1 else V.copy()
    out = np.full((grid.size, Y.shape[1]), np.nan)
    for k in range(Y.shape[1]):
        scale = float(np.ptp(Y[valid[:, k], k])) if valid[:, k].any() else 0.0
        for j in range(len(V) - 1):
            if valid[j, k] and valid[j + 1, k]:
                out[j * n:(j + 1) * n, k] = hermite_step(V[j], V[j + 1], Y[j, k], Y[j + 1, k],
                                                          dY[j, k], dY[j + 1, k], t, scale)
        if len(V) == 1 and valid[0, k]:
            out[0, k] = Y[0, k]
    return grid, out


def hermite_step(V0: float, V1: float, y0: float, y1: float, d0: float, d1: float,
                  t: np.ndarray, scale: float) -> np.ndarray:
    """The cubic Hermite curve of one speed step at the fractions `t` (the engine's model of a
    step, :func:`propwhirl.engine.hermite.hermite_coeffs`), straight where it leaves the band
    of its end values widened by their difference and a quarter of the curve's whole range
    `scale`."""
    seg = hermite_eval(hermite_coeffs(y0, y1, d0, d1, V1 - V0), t)
    lo, hi = min(y0, y1), max(y0, y1)
    room = (hi - lo) + 0.25 * scale
    if not np.isfinite(seg).all() or seg.min() < lo - room or seg.max() > hi + room:
        seg = y0 + t * (y1 - y0)     # near a branch point the slope is singular
    return seg


def fine_sweep(analysis: "ModelAnalysis", model: "Model", speeds=None,
               n_speeds: int = FINE_SPEEDS) -> "Sweep":
    """The tracked sweep of `model` on a fine grid, its modes named as by ``analyse``.

    `speeds`: the grid [m/s] (increasing, > 0); default `n_speeds` speeds evenly from the
    analysis's first to its last speed.  `model` must be the analysed model (its modes must
    carry the analysis's names): otherwise an InputError.

    Parameters
    ----------
    analysis : ModelAnalysis
        The analysis whose mode names the sweep takes.
    model : Model
        The analysed model.
    speeds : array_like, optional
        The grid [m/s], increasing, > 0.
    n_speeds : int
        Number of speeds of the default grid.

    Returns
    -------
    Sweep
        λ [1/s] of every mode along the speeds [m/s] (with refinement points), named.

    Examples
    --------
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> model = isolated_baseline_propeller()
    >>> a = analyse(model, speeds=[100.0, 200.0, 250.0])
    >>> from propwhirl.app.plots import fine_sweep
    >>> sw = fine_sweep(a, model, n_speeds=11)
    >>> float(sw.V[0]), float(sw.V[-1]), sw.V.size >= 11, sw.mode_labels[:2]
    (100.0, 250.0, True, ('backward', 'forward'))
    """
    sw0 = analysis.sweep
    if speeds is None:
        n = v.integer_at_least("n_speeds", n_speeds, 2)
        speeds = np.linspace(float(sw0.V[0]), float(sw0.V[-1]), n)
    dm = model.dof_map()
    n_analysed = len(sw0.state_labels)       # full-order states, also of a reduced analysis
    if dm.n_states != n_analysed:
        raise v.InputError(f"model {getattr(model, 'name', '?')!r} has {dm.n_states} states, the "
                           f"analysis {n_analysed}: pass the analysed model")
    sw = engine_sweep(model.assembly().state_matrix, speeds, displacement=dm.displacement,
                      state_labels=dm.state_labels)
    sw = sw.relabel(mode_names(model, sw))
    missing = sorted(set(sw0.mode_labels) - set(sw.mode_labels))
    named = [lab for lab in sw0.mode_labels if not is_lag(lab) and "'" not in lab]
    if any(lab in missing for lab in named):
        raise v.InputError(f"the model's modes are not the analysis's (missing {missing[:4]}): "
                           "pass the analysed model")
    return sw


def _oscillatory(sw: "Sweep") -> np.ndarray:
    lam = sw.eigenvalues
    return sw.physical & (np.abs(lam.imag) > _REAL * np.maximum(np.abs(lam), 1.0))


def damping_fall(sw: "Sweep") -> np.ndarray:
    """(n, 2): each mode's peak ζ over the range and the lowest ζ after that peak (where
    the root is oscillatory; NaN-free: +inf where never oscillatory)."""
    return damping_fall_of(np.where(_oscillatory(sw), sw.damping_ratio, np.nan))


def damping_fall_of(z: np.ndarray) -> np.ndarray:
    """:func:`damping_fall` of ζ (T, n), NaN where not oscillatory."""
    out = np.full((z.shape[1], 2), np.inf)
    for k in range(z.shape[1]):
        zk = z[:, k]
        if np.isnan(zk).all():
            continue
        t = int(np.nanargmax(zk))
        out[k] = float(zk[t]), float(np.nanmin(zk[t:]))
    return out


def select_modes(analysis: "ModelAnalysis", n_modes: int | None = None,
                 labels: Sequence[str] | None = None, include_lag: bool = False, *,
                 sweep: "Sweep | None" = None, margin: float | None = DAMPING_MARGIN,
                 max_frequency_hz: float | None = None) -> list[int]:
    """Mode ids of `sweep` (default the analysis's) to plot, lowest frequency first.

    Candidates: the physical modes at the first speed (lag roots only with `include_lag`).
    The modes that *matter*: those with an instability in the analysis and those whose ζ,
    after its peak, falls back below `margin` (by more than margin/2: :func:`damping_fall`;
    at low speed every mode has only its small structural damping, which is not a trend to
    an instability).  Drawn: the modes that
    matter and every candidate whose frequency at the first speed is at most
    `max_frequency_hz` [Hz] (default :data:`CUTOFF_FACTOR` × the highest frequency a mode
    that matters reaches; if none matters, the four least damped modes matter).
    `margin=None`: every candidate (the former behaviour), optionally cut at
    `max_frequency_hz`.  `labels`: exactly these modes.  `n_modes`: at most n, the modes that
    matter first, then by frequency.

    Parameters
    ----------
    analysis : ModelAnalysis
        The analysis (its events decide which modes matter).
    n_modes : int, optional
        At most this many modes.
    labels : sequence of str, optional
        Exactly these modes (by name).
    include_lag : bool
        Aerodynamic lag roots are candidates too.
    sweep : Sweep, optional
        The sweep whose mode ids are returned (default the analysis's; e.g.
        :func:`fine_sweep`'s).
    margin : float or None
        Damping-ratio margin ζ [-] (default :data:`DAMPING_MARGIN`); None: every candidate.
    max_frequency_hz : float, optional
        Frequency cut-off [Hz] at the first speed.

    Returns
    -------
    list of int
        Mode ids, lowest frequency first.

    Examples
    --------
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.app.plots import select_modes
    >>> from propwhirl.cases.ch10_other_wings import wingtip_propeller_wing
    >>> a = analyse(wingtip_propeller_wing())
    >>> [a.sweep.mode_labels[k] for k in select_modes(a)]
    ['wing 1', 'backward 1', 'forward 1']
    """
    sw = analysis.sweep if sweep is None else sweep
    phys0 = sw.physical[0]
    ids = [k for k in range(sw.n_modes) if phys0[k]
           and (include_lag or not is_lag(sw.mode_labels[k]))]
    f0 = sw.frequency_hz[0]
    if labels is not None:
        unknown = [lab for lab in labels if lab not in sw.mode_labels]
        if unknown:
            raise v.InputError(f"mode labels {unknown} not in the analysis: modes are "
                               f"{', '.join(sw.mode_labels[k] for k in ids)}")
        ids = [k for k in ids if sw.mode_labels[k] in labels]
        matter: list[int] = []
    else:
        if max_frequency_hz is not None:
            v.positive("max_frequency_hz", max_frequency_hz, "Hz")
        if margin is None:
            matter = []
            if max_frequency_hz is not None:
                ids = [k for k in ids if f0[k] <= max_frequency_hz]
        else:
            v.finite("margin", margin)
            fall = damping_fall(sw)
            unstable = {e.label for e in analysis.events}
            matter = [k for k in ids if sw.mode_labels[k] in unstable
                      or (fall[k, 1] < margin and fall[k, 0] - fall[k, 1] > 0.5 * margin)]
            if not matter:
                matter = sorted(ids, key=lambda k: fall[k, 1] - fall[k, 0])[:4]
            if max_frequency_hz is None:
                fmax = np.where(sw.physical, sw.frequency_hz, 0.0)[:, matter].max(initial=0.0)
                max_frequency_hz = CUTOFF_FACTOR * float(fmax)
            ids = [k for k in ids if k in matter or f0[k] <= max_frequency_hz]
    ids.sort(key=lambda k: (k not in matter if n_modes is not None else False, f0[k], k))
    if n_modes is not None:
        ids = ids[: v.integer_at_least("n_modes", n_modes, 1)]
    ids.sort(key=lambda k: (round(float(f0[k]), 6), _natural(sw.mode_labels[k]), k))
    return ids


def _natural(label: str) -> tuple:
    """'forward 10' after 'forward 2'."""
    head, _, num = label.rpartition(" ")
    return (head, int(num)) if num.isdigit() else (label, 0)


def emphasised_modes(analysis: "ModelAnalysis", sw: "Sweep", ids: Sequence[int],
                     margin: float | None = DAMPING_MARGIN) -> list[int]:
    """The modes of `ids` (ids of `sw`) drawn bold and labelled: those with an instability of
    the analysis in the range of `sw` and those whose ζ, after its peak, falls below `margin`
    (default :data:`DAMPING_MARGIN` when None) by more than margin/2 (:func:`damping_fall`);
    if there are none, the (at most four) least damped modes by that fall."""
    fall = damping_fall(sw)[list(ids)]
    keep = emphasised([sw.mode_labels[k] for k in ids], fall, analysis.events,
                       (float(sw.V[0]), float(sw.V[-1])), margin)
    return [k for k, bold in zip(ids, keep) if bold]


def emphasised(labels: Sequence[str], fall: np.ndarray, events: Sequence,
                speeds: tuple[float, float],
                margin: float | None = DAMPING_MARGIN) -> list[bool]:
    """Which of the modes named `labels` (their :func:`damping_fall` `fall`) a V-g-f over
    `speeds` [m/s] emphasises (:func:`emphasised_modes`)."""
    m = DAMPING_MARGIN if margin is None else float(margin)
    with_event = {e.label for e in events if speeds[0] <= e.V <= speeds[1]}
    out = [j for j in range(len(labels)) if labels[j] in with_event
           or (fall[j, 1] < m and fall[j, 0] - fall[j, 1] > 0.5 * m)]
    if not out:
        out = sorted(range(len(labels)), key=lambda j: fall[j, 1] - fall[j, 0])[:4]
    return [j in out for j in range(len(labels))]


def vgf(analysis: "ModelAnalysis", model: "Model | None" = None, *, speeds=None,
        n_speeds: int = FINE_SPEEDS, margin: float | None = DAMPING_MARGIN,
        max_frequency_hz: float | None = None, n_modes: int | None = None,
        labels: Sequence[str] | None = None, include_lag: bool = False,
        title: str | None = None, path: str | Path | None = None,
        requirements: "VgfRequirements | None" = None, hermite: bool = False) -> "Figure":
    """V-g-f diagram of an analysis: ζ and f [Hz] against V [m/s] of the modes that matter
    (drawn by :func:`vgf_figure`).

    Laid out for many modes: each mode coloured by its family
    (:func:`~propwhirl.analysis.naming.mode_family`: wing bending blue, wing torsion purple,
    backward whirl red, forward whirl green, in-plane orange; shades within a family); the
    modes with an instability in range or whose damping falls below the margin
    (:func:`emphasised_modes`) bold and named in the legend, the others thin and pale; the ζ
    axis around the region that matters (from ζ = −0.05 or below to a little above the
    highest damping of the emphasised flutter and near-critical modes, at most
    :data:`ZETA_TOP`), the frequency axis to the emphasised modes' highest frequency plus a
    margin; where a curve leaves the ζ axis a triangle marks it.  Every instability in range
    is marked and labelled "what of which mode, V m/s, f Hz", the labels placed where they
    collide with no other label or marker (:func:`~propwhirl.app.plots.layout.place_labels`).

    Parameters
    ----------
    analysis : ModelAnalysis
        From :func:`propwhirl.analysis.analyse` (or re-read with ``load``).
    model : Model, optional
        The analysed model: the curves are then computed on a fine grid (:func:`fine_sweep`,
        `speeds` or `n_speeds` speeds; a few seconds for large models).  Without it the
        analysis's own sweep is drawn (coarse unless analysed with ``vgf=True``).
    speeds : array_like, optional
        The fine grid [m/s] with `model` (default `n_speeds` speeds evenly over the
        analysis's range).
    n_speeds : int
        Number of speeds of the default fine grid.
    margin : float or None
        Damping margin of :func:`select_modes` (default :data:`DAMPING_MARGIN` = 0.03): modes
        whose ζ falls below it are drawn; None draws every mode.
    max_frequency_hz : float, optional
        Frequency cut-off [Hz] of :func:`select_modes`.
    n_modes, labels, include_lag
        As in :func:`select_modes`.
    title, path
        Figure title; file to write (PNG, or the format of the suffix).
    requirements : VgfRequirements, optional
        The clearance's lines: V_D, the required speed (``analyse --vd``), a damping
        requirement.
    hermite : bool
        Without `model`: draw the analysis's own sweep as cubic Hermite curves through its
        speeds (dots), from the exact slopes dλ/dV (:func:`hermite_columns`, as a campaign's
        V-g-f) — no second sweep; the curves are exact at the analysed speeds and the
        crossings are the analysis's refined ones.

    Returns
    -------
    matplotlib.figure.Figure
        Two axes (ζ with the unstable half shaded and a g = 2ζ scale on the right; f), one
        line per mode in each, the instabilities marked and annotated "V m/s, f Hz".

    Examples
    --------
    The isolated baseline propeller (§9.2) on 11 speeds; the figure is drawn on an Agg
    canvas (no window; ``path=`` writes it):

    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> model = isolated_baseline_propeller()
    >>> a = analyse(model, speeds=[100.0, 200.0, 250.0])
    >>> from propwhirl.app.plots import vgf
    >>> fig = vgf(a, model, n_speeds=11)
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['damping ratio ζ  (ζ < 0: unstable)', 'frequency f [Hz]']
    >>> fig.axes[1].get_xlabel()
    'airspeed V [m/s]'
    """
    matplotlib_or_error()
    sw = analysis.sweep if model is None else fine_sweep(analysis, model, speeds, n_speeds)
    ids = select_modes(analysis, n_modes, labels, include_lag, sweep=sw, margin=margin,
                       max_frequency_hz=max_frequency_hz)
    if not ids:
        raise v.InputError("no modes to plot: the selection is empty")
    bold = emphasised_modes(analysis, sw, ids, margin)
    names = [sw.mode_labels[k] for k in ids]
    V = np.asarray(sw.V, dtype=float)
    zeta = np.where(_oscillatory(sw), sw.damping_ratio, np.nan)[:, ids]
    freq = np.where(sw.physical, sw.frequency_hz, np.nan)[:, ids]
    nodes = None
    if hermite and model is None:          # the analysis's own speeds, smooth between them
        dlam = np.asarray(sw.dlam_dV)[:, ids]
        lam = np.asarray(sw.eigenvalues)[:, ids]
        mag = np.where(np.abs(lam) > 0, np.abs(lam), 1.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            dmag = (lam.real * dlam.real + lam.imag * dlam.imag) / mag
            dzeta = -(dlam.real * mag - lam.real * dmag) / mag**2
        valid = np.isfinite(zeta) & np.isfinite(dzeta)
        nodes = (V, zeta, freq)
        Vs, zeta_s = hermite_columns(V, np.nan_to_num(zeta), np.nan_to_num(dzeta), valid)
        _, freq_s = hermite_columns(V, np.nan_to_num(freq), np.nan_to_num(dlam.imag / (2 * np.pi)),
                                    valid & np.isfinite(freq))
        V, zeta, freq = Vs, zeta_s, freq_s
    curves = VgfCurves(
        V=V, zeta=zeta, frequency_hz=freq,
        labels=tuple(names), names=tuple(analysis.describe(n) for n in names),
        families=tuple(mode_family(n, analysis.content.get(n)) for n in names),
        bold=tuple(k in bold for k in ids), nodes=nodes)
    grid = f"{sw.V.size} speeds" + ("" if model is None else ", fine grid") + (
        ", the analysis's own" if nodes is not None else "")
    head = f"{analysis.model_name}: V-g-f ({grid})"
    if len(head) > 80:
        head = f"{analysis.model_name}\nV-g-f ({grid})"
    fig = vgf_figure(curves, [VgfEvent(e.kind, e.event, e.label, e.V, e.frequency_hz)
                              for e in analysis.events], margin=margin, title=title or head,
                     requirements=requirements)
    return finish(fig, path)


class VgfEvent(NamedTuple):
    """An instability as a V-g-f marks it: kind ("flutter", "divergence"), event ("onset",
    "recovery", "frequency-zero", "unstable-at-start"), label (its mode's name), V [m/s] and
    frequency_hz [Hz] (an analysis's :class:`~propwhirl.analysis.events.Instability` has
    them all)."""

    kind: str
    event: str
    label: str
    V: float
    frequency_hz: float


@dataclass(frozen=True)
class VgfCurves:
    """The curves of a V-g-f, whatever they were read from.

    V:            (S,) increasing airspeeds of the drawn curves [m/s].
    zeta:         (S, n) damping ratio ζ [-] of each mode where it oscillates, NaN elsewhere.
    frequency_hz: (S, n) frequency f [Hz] where it is drawn, NaN elsewhere.
    labels:       n mode names (the events' ``label``).
    names:        n texts of the legend and the labels (the name with its content,
                  :meth:`~propwhirl.analysis.stability.ModelAnalysis.describe`).
    families:     n families (:func:`propwhirl.analysis.naming.mode_family`).
    bold:         n flags: emphasised (bold, named in the legend, its least damping labelled
                  when it has no event) or thin, pale and counted by family in the legend.
    nodes:        the speeds the curves were computed from, drawn as dots: (V (T,) [m/s],
                  ζ (T, n), f (T, n) [Hz], NaN where not drawn), or None.
    """

    V: np.ndarray
    zeta: np.ndarray
    frequency_hz: np.ndarray
    labels: tuple[str, ...]
    names: tuple[str, ...]
    families: tuple[str, ...]
    bold: tuple[bool, ...]
    nodes: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None


@dataclass(frozen=True)
class VgfRequirements:
    """The clearance requirements a V-g-f draws (a campaign point's): the design dive speed
    V_D and the required speed [m/s] (vertical lines, annotated), the damping requirement
    g = 2ζ ≥ ``min_damping_g`` up to V_D (a line in the ζ axes, None: none) and the critical
    speed [m/s] of the kind ``critical_kind`` ("flutter", "divergence"; a ring round its
    marker at ζ = 0, "V_crit" in the legend; None: none).

    Parameters
    ----------
    V_D : float
        The design dive speed [m/s] (a dotted vertical line).
    V_required : float
        The required speed [m/s], e.g. 1.15 V_D (a dashed vertical line).
    min_damping_g : float, optional
        The damping requirement g = 2ζ [-], drawn as ζ = g/2 up to V_D.
    critical_speed : float, optional
        The critical speed [m/s] (a ring at ζ = 0).
    critical_kind : str
        Its kind, "flutter" or "divergence".

    Examples
    --------
    ``propwhirl analyse --vd 90 --plot`` draws V_D and 1.15 V_D:

    >>> from propwhirl.app.plots import VgfRequirements
    >>> r = VgfRequirements(90.0, 1.15 * 90.0)
    >>> round(r.V_required, 2), r.min_damping_g
    (103.5, None)
    """

    V_D: float
    V_required: float
    min_damping_g: float | None = None
    critical_speed: float | None = None
    critical_kind: str = "flutter"


#: colour of the V_D, required-speed and damping-requirement lines
REQUIREMENT_COLOUR = "0.15"


def vgf_figure(curves: VgfCurves, events: Sequence[VgfEvent], *,
               margin: float | None = DAMPING_MARGIN, title: str = "",
               requirements: VgfRequirements | None = None, label_least_damped: bool = True,
               xlabel: str = "airspeed V [m/s]",
               figsize: tuple[float, float] = (11.0, 7.5),
               zeta_limits: tuple[float, float] | None = None) -> "Figure":
    """The V-g-f figure: ζ and f [Hz] against V [m/s] of ``curves``, the instabilities of
    ``events`` marked and labelled — the one drawing of every V-g-f (:func:`vgf`,
    :func:`propwhirl.app.plots.campaign_plot.point_vgf`).

    Each mode coloured by its family (:data:`~propwhirl.app.plots.layout.FAMILY_COLOURS`,
    shades within a family: :func:`~propwhirl.app.plots.layout.family_shades`), the bold
    ones named in the legend, the thin ones counted there by family (an aerodynamic lag root,
    drawn only when asked for, is no mode of a family: counted apart); the ζ axis around the
    region that matters (:func:`_zeta_window`, from −0.05 or below to a little above the
    highest damping of the bold flutter and near-critical modes, at most :data:`ZETA_TOP`;
    up to the damping requirement), the frequency axis to the bold modes' highest frequency
    plus a margin; a triangle where a curve leaves the ζ axis.  The events of the drawn
    modes in range are marked (flutter red, divergence green; filled at an onset, open at a
    recovery) and labelled "what of which mode, V m/s, f Hz", as is each bold mode's least
    damping after its peak where it has no event (``label_least_damped``), the labels placed
    where they collide with no other label, marker or annotation
    (:func:`~propwhirl.app.plots.layout.place_labels`).  ``requirements``: the clearance's
    lines (:class:`VgfRequirements`).  ``margin``: the damping margin of the ζ axis (None:
    :data:`DAMPING_MARGIN`).  ``zeta_limits``: the ζ axis (lo, hi) instead (a campaign's
    band that decides: :func:`propwhirl.app.plots.campaign_plot.deciding_band`).  Returns the
    figure, its layout frozen (not yet saved).
    """
    matplotlib_or_error()
    style = _curve_styles(curves)
    fig = new_figure(figsize=figsize, layout="constrained")
    ax_z, ax_f = fig.subplots(2, 1, sharex=True)
    V = np.asarray(curves.V, dtype=float)
    z_all = np.asarray(curves.zeta, dtype=float)
    f_all = np.asarray(curves.frequency_hz, dtype=float)
    zlim = (_zeta_limits(events, curves.labels, style.bold, z_all, margin, requirements)
            if zeta_limits is None else tuple(float(x) for x in zeta_limits))
    drawn = _draw_curves(ax_z, ax_f, curves, style, zlim)
    ax_z.axhspan(zlim[0], 0.0, facecolor=FLUTTER_COLOUR, alpha=0.07, lw=0, zorder=0,
                 label="unstable (ζ < 0)")
    ax_z.axhline(0.0, color="0.3", lw=0.8)
    marked = _mark_events(events, drawn, ax_z, ax_f, (float(V[0]), float(V[-1])))
    extra = [] if requirements is None else _draw_requirements(ax_z, ax_f, V, requirements)
    _set_axes(ax_z, ax_f, V, f_all, style, zlim, xlabel)
    handles, names = _legend_entries(ax_z, curves, style, extra)
    fig.legend(handles, names, loc="outside right upper", fontsize=8)
    ax_z.set_title(title, fontsize=11)
    freeze_layout(fig)
    _label_events(ax_z, marked, dict(zip(curves.labels, curves.names)), V, curves.labels,
                  style.bold if label_least_damped else [], z_all, zlim)
    return fig


class _Styles(NamedTuple):
    """How :func:`vgf_figure` draws the columns of its curves: bold and thin (their
    indices), the bold ones in the order of :data:`FAMILY_COLOURS` (``order``), each
    column's family and colour (shades within a family: bold and thin shaded apart)."""

    bold: list[int]
    thin: list[int]
    order: list[int]
    family: dict[int, str]
    colour: dict[int, object]


def _curve_styles(curves: VgfCurves) -> _Styles:
    """The :class:`_Styles` of ``curves`` (their ``bold`` flags and ``families``)."""
    cols = list(range(len(curves.labels)))
    bold = [j for j in cols if curves.bold[j]]
    thin = [j for j in cols if not curves.bold[j]]
    family = dict(zip(cols, curves.families))
    rank = list(FAMILY_COLOURS).index
    order = sorted(bold, key=lambda j: rank(family[j]))
    colour = dict(zip(order, family_shades([family[j] for j in order])))
    thin_order = sorted(thin, key=lambda j: rank(family[j]))
    colour.update(zip(thin_order, family_shades([family[j] for j in thin_order])))
    return _Styles(bold, thin, order, family, colour)


def _zeta_limits(events: Sequence[VgfEvent], labels: Sequence[str], bold: Sequence[int],
                 z: np.ndarray, margin: float | None,
                 req: VgfRequirements | None) -> tuple[float, float]:
    """The ζ axis's limits: :func:`_zeta_window`, raised to show a damping requirement
    (half its g, with room above)."""
    lo, hi = _zeta_window(events, labels, bold, z, margin)
    if req is not None and req.min_damping_g is not None:
        hi = max(hi, 0.5 * float(req.min_damping_g) * 1.15)
    return lo, hi


def _draw_curves(ax_z, ax_f, curves: VgfCurves, style: _Styles,
                 zlim: tuple[float, float]) -> dict[str, object]:
    """Each mode's ζ and f against V (thin ones first, then the bold in family order), the
    speeds they were computed from as dots (``curves.nodes``), a triangle where a ζ curve
    leaves `zlim`; returns the drawn modes' colours by label."""
    V = np.asarray(curves.V, dtype=float)
    z_all = np.asarray(curves.zeta, dtype=float)
    f_all = np.asarray(curves.frequency_hz, dtype=float)
    drawn: dict[str, object] = {}
    for j in style.thin + style.order:
        strong = j in style.bold
        colour = style.colour[j]
        kw = dict(color=colour, lw=2.0 if strong else 0.9, alpha=1.0 if strong else 0.45,
                  zorder=3 if strong else 2)
        ax_z.plot(V, z_all[:, j], "-", label=curves.names[j], **kw)
        ax_f.plot(V, f_all[:, j], "-", **kw)
        if curves.nodes is not None:
            Vn, zn, fn = (np.asarray(x, dtype=float) for x in curves.nodes)
            for ax, y in ((ax_z, zn[:, j]), (ax_f, fn[:, j])):
                ok = np.isfinite(y)
                ax.plot(Vn[ok], y[ok], ".", ms=3, color=colour, zorder=kw["zorder"])
        _mark_clipping(ax_z, V, z_all[:, j], *zlim, colour, strong)
        drawn[curves.labels[j]] = colour
    return drawn


def _set_axes(ax_z, ax_f, V: np.ndarray, f_all: np.ndarray, style: _Styles,
              zlim: tuple[float, float], xlabel: str) -> None:
    """Limits, labels and grids: ζ in `zlim` with a g = 2ζ scale on the right, f [Hz] from 0
    to a little above the bold modes' highest frequency (every mode's when the bold ones
    have none), V [m/s] over the curves' range."""
    ax_z.set_ylim(*zlim)
    ax_z.set_ylabel(ZETA_LABEL)
    g_axis = ax_z.secondary_yaxis("right", functions=(lambda z: 2.0 * z, lambda g: 0.5 * g))
    g_axis.set_ylabel("g = 2ζ")
    bold, cols = style.bold, list(style.family)
    f_top = np.nanmax(f_all[:, bold]) if np.isfinite(f_all[:, bold]).any() else np.nan
    if not np.isfinite(f_top) or f_top <= 0:
        f_top = np.nanmax(f_all[:, cols]) if np.isfinite(f_all[:, cols]).any() else 1.0
    ax_f.set_ylim(0.0, 1.12 * float(f_top) if f_top > 0 else 1.0)
    ax_f.set_ylabel("frequency f [Hz]")
    ax_f.set_xlabel(xlabel)
    ax_f.set_xlim(V[0], V[-1])
    for ax in (ax_z, ax_f):
        ax.grid(True, alpha=0.3)


def _legend_entries(ax_z, curves: VgfCurves, style: _Styles,
                    extra: Sequence[tuple[object, str]]) -> tuple[list, list[str]]:
    """The legend's handles and texts: each bold mode by name, the thin ones counted by
    family (the aerodynamic lag roots apart), the unstable half, the markers, then the
    requirements' entries `extra`."""
    from matplotlib.lines import Line2D

    family = style.family
    handles = [Line2D([], [], color=style.colour[j], lw=2.0) for j in style.order]
    names = [wrap(curves.names[j], LEGEND_WRAP) for j in style.order]
    lags = [j for j in style.thin if is_lag(curves.labels[j])]
    for fam in FAMILY_COLOURS:
        n_thin = sum(family[j] == fam for j in style.thin if j not in lags)
        if n_thin:
            handles.append(Line2D([], [], color=FAMILY_COLOURS[fam], lw=0.9, alpha=0.45))
            names.append(f"{fam}: {n_thin} other mode{'s' if n_thin > 1 else ''}")
    if lags:
        handles.append(Line2D([], [], color=FAMILY_COLOURS["other"], lw=0.9, alpha=0.45))
        names.append(f"aerodynamic lag root{'s' if len(lags) > 1 else ''}: {len(lags)}")
    handles += [ax_z.patches[-1] if ax_z.patches else Line2D([], []),
                Line2D([], [], ls="", marker="o", mec=FLUTTER_COLOUR, mfc=FLUTTER_COLOUR, ms=8),
                Line2D([], [], ls="", marker="o", mec=DIVERGENCE_COLOUR, mfc=DIVERGENCE_COLOUR,
                       ms=8),
                Line2D([], [], ls="", marker="v", color="0.3", ms=6)]
    names += ["unstable (ζ < 0)", "flutter onset (open: recovery)",
              "divergence onset", "curve leaves the ζ axis"]
    handles += [h for h, _ in extra]
    names += [t for _, t in extra]
    return handles, names


def _draw_requirements(ax_z, ax_f, V: np.ndarray,
                       req: VgfRequirements) -> list[tuple[object, str]]:
    """The clearance's lines and annotations (:class:`VgfRequirements`); returns the legend
    entries (handle, text) of the damping requirement and the critical speed."""
    for ax in (ax_z, ax_f):
        ax.axvline(req.V_D, color=REQUIREMENT_COLOUR, lw=1.0, ls=":")
        ax.axvline(req.V_required, color=REQUIREMENT_COLOUR, lw=1.4, ls="--")
    ax_z.annotate(f"V_D {req.V_D:.1f} m/s", (req.V_D, 1.0), xycoords=("data", "axes fraction"),
                  xytext=(-3, -3), textcoords="offset points", ha="right", va="top", fontsize=8)
    ax_z.annotate(f"required {req.V_required:.1f} m/s", (req.V_required, 1.0),
                  xycoords=("data", "axes fraction"), xytext=(3, -3),
                  textcoords="offset points", ha="left", va="top", fontsize=8)
    out = []
    if req.min_damping_g is not None:
        g = float(req.min_damping_g)
        line, = ax_z.plot([float(V[0]), req.V_D], [0.5 * g] * 2, "-", color=REQUIREMENT_COLOUR,
                          lw=1.4)
        out.append((line, f"required g ≥ {g:g} (ζ ≥ {0.5 * g:g})"))
    if req.critical_speed is not None:          # a ring round the critical event's marker
        colour = FLUTTER_COLOUR if req.critical_kind == "flutter" else DIVERGENCE_COLOUR
        ring, = ax_z.plot([req.critical_speed], [0.0], "o", ms=14, mfc="none", mec=colour,
                          mew=1.2, zorder=5)
        out.append((ring, f"V_crit {req.critical_speed:.1f} m/s ({req.critical_kind})"))
    return out


#: the ζ axis never reaches above this (a mode damped more than this is far from flutter)
ZETA_TOP = 0.3
#: the ζ axis reaches at least this far below zero
ZETA_BOTTOM = -0.05
#: characters per line of a mode name in the legend
LEGEND_WRAP = 34


def _zeta_window(events: Sequence[VgfEvent], labels: Sequence[str], bold: Sequence[int],
                 z: np.ndarray, margin: float | None) -> tuple[float, float]:
    """ζ axis limits around the region that matters: the emphasised modes that flutter or
    come near it (not those emphasised only for a divergence: a real root's approach
    stretches ζ towards 1), up to a little above their highest damping before their
    lowest, at most :data:`ZETA_TOP`; below zero to :data:`ZETA_BOTTOM` or 0.8 × the top,
    whichever is lower (room for the labels in the unstable half)."""
    m = DAMPING_MARGIN if margin is None else abs(float(margin))
    flutter = {e.label for e in events if e.kind == "flutter"}
    diverging = {e.label for e in events if e.kind == "divergence"}
    rel = [k for k in bold if labels[k] in flutter
           or labels[k] not in diverging] or list(bold)
    zr = z[:, rel]
    finite = zr[np.isfinite(zr)]
    if finite.size == 0:
        return ZETA_BOTTOM, max(2.0 * m, 0.05)
    top = min(max(float(finite.max()), 2.0 * m, 1e-3), ZETA_TOP)
    hi = top + 0.15 * top
    lo = min(ZETA_BOTTOM, -0.8 * hi)
    return lo, hi


def _mark_clipping(ax, V: np.ndarray, z: np.ndarray, lo: float, hi: float, colour,
                   strong: bool) -> None:
    """A triangle where curve `z` leaves the ζ window [lo, hi] (▲ at the top, ▼ at the
    bottom), at the crossing speed on the axis edge; a curve that starts outside it, at its
    first speed."""
    inside = np.isfinite(z) & (z >= lo) & (z <= hi)
    finite = np.flatnonzero(np.isfinite(z))
    if finite.size and not inside[finite[0]]:
        edge = hi if z[finite[0]] > hi else lo
        ax.plot([V[finite[0]]], [edge], "^" if edge == hi else "v", color=colour,
                ms=7 if strong else 4.5, alpha=1.0 if strong else 0.6, clip_on=False, zorder=4)
    for i in np.flatnonzero(inside[:-1] & ~inside[1:] & np.isfinite(z[1:])):
        edge = hi if z[i + 1] > hi else lo
        t = (edge - z[i]) / (z[i + 1] - z[i]) if z[i + 1] != z[i] else 0.0
        ax.plot([V[i] + t * (V[i + 1] - V[i])], [edge], "^" if edge == hi else "v",
                color=colour, ms=7 if strong else 4.5, alpha=1.0 if strong else 0.6,
                clip_on=False, zorder=4)


def _mark_events(events: Sequence[VgfEvent], drawn: Mapping[str, object], ax_z, ax_f,
                 xlim: tuple[float, float]) -> list:
    """Markers of the drawn modes' events in range (flutter red, divergence green; filled
    at an onset, open at a recovery); returns those events, onsets first then by speed."""
    events = [e for e in events if e.label in drawn and xlim[0] <= e.V <= xlim[1]]
    for e in events:
        colour = FLUTTER_COLOUR if e.kind == "flutter" else DIVERGENCE_COLOUR
        face = colour if e.event != "recovery" else "none"
        for ax, y in ((ax_z, 0.0), (ax_f, e.frequency_hz)):
            ax.plot([e.V], [y], "o", ms=8, mec=colour, mfc=face, mew=1.8, zorder=5)
    return sorted(events, key=lambda e: (e.event == "recovery", e.V))


#: events of one kind closer than this fraction of the speed range share one label (a table)
CROWD = 0.03
#: longest row of such a table before a mode's name and its speed take two lines
WRAP_ROW = 52


def _where(e) -> str:
    """'80.0 m/s, 7.02 Hz' of an event (no frequency at a divergence)."""
    return f"{e.V:.1f} m/s" + (f", {e.frequency_hz:.2f} Hz" if e.kind == "flutter" else "")


def _split_name(name: str) -> tuple[str, str]:
    """('backward whirl, propellers 1–6', '2 of 6; pitch') of 'backward whirl, propellers
    1–6 (2 of 6; pitch)'; (name, '') without a trailing parenthesis."""
    head, sep, tail = name.partition(" (")
    return (head, tail[:-1]) if sep and tail.endswith(")") else (name, "")


def _table_rows(rows: Sequence[tuple[str, str]]) -> list[str]:
    """Rows 'name: where' of a crowd's label; names sharing their part before the
    parenthesis (a family of propellers) under one heading, one indented row per mode
    '  detail: where'; a row longer than :data:`WRAP_ROW` in two lines."""
    bases = [_split_name(name)[0] for name, _ in rows]
    out: list[str] = []
    for i, (name, where) in enumerate(rows):
        base, detail = _split_name(name)
        if detail and bases.count(base) > 1:
            if base not in bases[:i]:
                out.append(f"{base}:")
            line = f"  {detail}: {where}"
            out.append(line if len(line) <= WRAP_ROW else
                       f"  {detail}:\n     {where}")
            continue
        one = f"{name}: {where}"
        out.append(one if len(one) <= WRAP_ROW else f"{wrap(name)}:\n   {where}")
    return out


def _crowds(events, gap: float) -> list[list]:
    """The events in groups of one kind and event type whose speeds follow each other within
    `gap` [m/s] (each group sorted by speed); groups in the order of their first event."""
    groups: list[list] = []
    for e in sorted(events, key=lambda e: (e.event == "recovery", e.V)):
        for g in groups:
            if (g[-1].kind, g[-1].event) == (e.kind, e.event) and e.V - g[-1].V <= gap:
                g.append(e)
                break
        else:
            groups.append([e])
    return groups


_WHAT = {"onset": "{kind} of {mode}", "recovery": "{kind} recovery of {mode}",
         "frequency-zero": "divergence (f → 0) of {mode}",
         "unstable-at-start": "{mode} unstable from the start"}


def _label_events(ax_z, events, describe: Mapping[str, str], V: np.ndarray,
                  labels: Sequence[str], bold, z: np.ndarray, zlim) -> None:
    """Label every event in range ("flutter of <mode>", V [m/s], f [Hz]; events of one kind
    within :data:`CROWD` of the speed range of each other in one table-like label, one row
    per mode) and each emphasised mode (columns ``bold`` of ``z``, named ``labels``) without
    one (its least damping after its peak), no label on another, on a marker or on an
    annotation already there (:func:`~propwhirl.app.plots.layout.place_labels`).
    ``describe``: the text of each mode's name."""
    span = float(V[-1] - V[0]) or 1.0
    labelled = {e.label for e in events}
    rows = _event_labels(events, describe, CROWD * span) + _least_damping_labels(
        [k for k in bold if labels[k] not in labelled], describe, V, labels, z, zlim)
    anchors, texts, cols, aligns = (list(x) for x in zip(*rows)) if rows else ([], [], [], [])
    avoid, soft = _obstacles(ax_z)
    place_labels(ax_z, anchors, texts, cols, avoid=avoid, soft=soft, prefer="below",
                 gid=LABEL_GID, aligns=aligns)


#: A label to place: its anchor (V [m/s], ζ), text, colour and horizontal alignment.
_Label = tuple[tuple[float, float], str, object, str]


def _event_labels(events, describe: Mapping[str, str], gap: float) -> list[_Label]:
    """One label per crowd of events (:func:`_crowds` within `gap` [m/s]) at ζ = 0: "flutter
    onset of <mode>" and where for one event, a table of its modes for several."""
    out: list[_Label] = []
    for group in _crowds(events, gap):
        e = group[0]
        colour = FLUTTER_COLOUR if e.kind == "flutter" else DIVERGENCE_COLOUR
        if len(group) == 1:
            what = _WHAT.get(e.event, "{kind} " + e.event + " of {mode}").format(
                kind=e.kind, mode=describe.get(e.label, e.label))
            out.append(((e.V, 0.0), f"{wrap(what)}\n{_where(e)}", colour, "center"))
            continue
        head = _WHAT.get(e.event, "{kind} " + e.event + " of {mode}").format(
            kind=e.kind, mode=f"{len(group)} modes")
        out.append(((e.V, 0.0), head + "\n" + "\n".join(_table_rows(
            [(describe.get(g.label, g.label), _where(g)) for g in group])), colour, "left"))
    return out


def _least_damping_labels(columns: Sequence[int], describe: Mapping[str, str], V: np.ndarray,
                          labels: Sequence[str], z: np.ndarray, zlim) -> list[_Label]:
    """A label at the least damping after its peak of each of the `columns` of `z` (the
    emphasised modes without an event) that lies in the ζ window `zlim`."""
    out: list[_Label] = []
    lo, hi = zlim
    for k in columns:
        zk = z[:, k]
        if not np.isfinite(zk).any():
            continue
        t0 = int(np.nanargmax(zk))
        t = t0 + int(np.nanargmin(zk[t0:]))
        if not lo <= zk[t] <= hi:
            continue
        name = describe.get(labels[k], labels[k])
        out.append(((float(V[t]), float(zk[t])),
                    f"{wrap(name)}\nζ min {zk[t]:.3f} at {V[t]:.0f} m/s", "0.2", "center"))
    return out


def _obstacles(ax_z) -> tuple[list, list]:
    """What a label may not cover (the event markers, the annotations already there: V_D,
    ...) and what it should rather not (the bold curves' boxes), in display units."""
    renderer = ax_z.figure.canvas.get_renderer()
    avoid = [ln.get_window_extent(renderer) for ln in ax_z.get_lines()
             if ln.get_marker() == "o"]
    avoid += [t.get_window_extent(renderer) for t in ax_z.texts]
    bold_lines = [ln for ln in ax_z.get_lines() if ln.get_linewidth() >= 2.0
                  and ln.get_linestyle() == "-"]
    return avoid, curve_boxes(ax_z, bold_lines)


#: ``gid`` of the labels of the V-g-f and Campbell diagrams (tests find them by it)
LABEL_GID = "label"
