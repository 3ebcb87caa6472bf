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
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from propwhirl import validate as v
from propwhirl.app.plots.canvas import (DIVERGENCE_COLOUR, FLUTTER_COLOUR, colours, finish,
                                        new_figure)

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


def fine_sweep(analysis: "ModelAnalysis", model: "Model", speeds=None,
               n_speeds: int = FINE_SPEEDS) -> "Sweep":
    """The tracked sweep of `model` on a fine grid, its modes named as by ``analyse``.

    `speeds`: the grid [m/s] (increasing, > 0); default `n_speeds` speeds evenly from the
    analysis's first to its last speed.  `model` must be the analysed model (its modes must
    carry the analysis's names): otherwise an InputError.
    """
    from propwhirl.analysis.naming import mode_names
    from propwhirl.engine import sweep as engine_sweep

    sw0 = analysis.sweep
    if speeds is None:
        n = v.integer_at_least("n_speeds", n_speeds, 2)
        speeds = np.linspace(float(sw0.V[0]), float(sw0.V[-1]), n)
    dm = model.dof_map()
    if dm.n_states != sw0.eigenvalues.shape[1]:
        raise v.InputError(f"model {getattr(model, 'name', '?')!r} has {dm.n_states} states, the "
                           f"analysis {sw0.eigenvalues.shape[1]}: pass the analysed model")
    sw = engine_sweep(model.assembly().state_matrix, speeds, displacement=dm.displacement,
                      state_labels=dm.state_labels)
    sw = sw.relabel(mode_names(model, sw))
    missing = sorted(set(sw0.mode_labels) - set(sw.mode_labels))
    named = [lab for lab in sw0.mode_labels if not lab.startswith("lag") and "'" not in lab]
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
    z = np.where(_oscillatory(sw), sw.damping_ratio, np.nan)
    out = np.full((sw.n_modes, 2), np.inf)
    for k in range(sw.n_modes):
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
    """
    sw = analysis.sweep if sweep is None else sweep
    phys0 = sw.physical[0]
    ids = [k for k in range(sw.n_modes) if phys0[k]
           and (include_lag or not sw.mode_labels[k].startswith("lag"))]
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


def vgf(analysis: "ModelAnalysis", model: "Model | None" = None, *, speeds=None,
        n_speeds: int = FINE_SPEEDS, margin: float | None = DAMPING_MARGIN,
        max_frequency_hz: float | None = None, n_modes: int | None = None,
        labels: Sequence[str] | None = None, include_lag: bool = False,
        title: str | None = None, path: str | Path | None = None) -> "Figure":
    """V-g-f diagram of an analysis: ζ and f [Hz] against V [m/s] of the modes that matter.

    Parameters
    ----------
    analysis : ModelAnalysis
        From :func:`propwhirl.analysis.analyse` (or re-read with ``load``).
    model : Model, optional
        The analysed model: the curves are then computed on a fine grid (:func:`fine_sweep`,
        `speeds` or `n_speeds` speeds; a few seconds for large models).  Without it the
        analysis's own sweep is drawn (coarse unless analysed with ``vgf=True``).
    margin : float or None
        Damping margin of :func:`select_modes` (default :data:`DAMPING_MARGIN` = 0.03): modes
        whose ζ falls below it are drawn; None draws every mode.
    max_frequency_hz : float, optional
        Frequency cut-off [Hz] of :func:`select_modes`.
    n_modes, labels, include_lag
        As in :func:`select_modes`.
    title, path
        Figure title; file to write (PNG, or the format of the suffix).

    Returns
    -------
    matplotlib.figure.Figure
        Two axes (ζ with the unstable half shaded and a g = 2ζ scale on the right; f), one
        line per mode in each, the instabilities marked and annotated "V m/s, f Hz".
    """
    sw = analysis.sweep if model is None else fine_sweep(analysis, model, speeds, n_speeds)
    ids = select_modes(analysis, n_modes, labels, include_lag, sweep=sw, margin=margin,
                       max_frequency_hz=max_frequency_hz)
    if not ids:
        raise v.InputError("no modes to plot: the selection is empty")
    fig = new_figure(figsize=(10.0, 7.0), layout="constrained")
    ax_z, ax_f = fig.subplots(2, 1, sharex=True)
    cmap = colours(len(ids))
    V = sw.V
    zeta, freq, osc = sw.damping_ratio, sw.frequency_hz, _oscillatory(sw)
    drawn: dict[str, object] = {}
    for colour, k in zip(cmap, ids):
        name = sw.mode_labels[k]
        ax_z.plot(V, np.where(osc[:, k], zeta[:, k], np.nan), "-", color=colour, lw=1.5,
                  label=analysis.describe(name))
        ax_f.plot(V, np.where(sw.physical[:, k], freq[:, k], np.nan), "-", color=colour, lw=1.5)
        drawn[name] = colour
    z_drawn = np.where(osc[:, ids], zeta[:, ids], np.nan)
    lo, hi = _zeta_limits(z_drawn)
    ax_z.axhspan(lo, 0.0, facecolor=FLUTTER_COLOUR, alpha=0.07, lw=0, zorder=0,
                 label="unstable (ζ < 0)")
    ax_z.axhline(0.0, color="0.3", lw=0.8)
    _mark_events(analysis, drawn, ax_z, ax_f, (lo, hi), (float(V[0]), float(V[-1])))
    ax_z.set_ylim(lo, hi)
    ax_z.set_ylabel(ZETA_LABEL)
    g_axis = ax_z.secondary_yaxis("right", functions=(lambda z: 2.0 * z, lambda g: 0.5 * g))
    g_axis.set_ylabel("g = 2ζ")
    f_top = np.nanmax(np.where(sw.physical[:, ids], freq[:, ids], np.nan))
    ax_f.set_ylim(0.0, 1.08 * float(f_top) if f_top > 0 else 1.0)
    ax_f.set_ylabel("frequency f [Hz]")
    ax_f.set_xlabel("airspeed V [m/s]")
    ax_f.set_xlim(V[0], V[-1])
    for ax in (ax_z, ax_f):
        ax.grid(True, alpha=0.3)
    from matplotlib.lines import Line2D

    handles, names = ax_z.get_legend_handles_labels()
    handles += [Line2D([], [], ls="", marker="o", mec=FLUTTER_COLOUR, mfc=FLUTTER_COLOUR, ms=8),
                Line2D([], [], ls="", marker="o", mec=DIVERGENCE_COLOUR, mfc=DIVERGENCE_COLOUR,
                       ms=8)]
    names += ["flutter onset", "divergence onset"]
    fig.legend(handles, names, loc="outside right upper", fontsize=9)
    grid = f"{V.size} speeds" + ("" if model is None else ", fine grid")
    ax_z.set_title(title or f"{analysis.model_name}: V-g-f ({grid})")   # over the axes: clear
    #                                                                      of the legend
    return finish(fig, path)


def _mark_events(analysis, drawn: dict, ax_z, ax_f, zlim: tuple[float, float],
                 xlim: tuple[float, float] | None = None) -> None:
    """Markers of the drawn modes' events; onsets annotated with V [m/s] and f [Hz], the
    labels spread so that they do not overlap."""
    events = [e for e in analysis.events if e.label in drawn]
    notes = []
    for e in events:
        colour = FLUTTER_COLOUR if e.kind == "flutter" else DIVERGENCE_COLOUR
        face = colour if e.event != "recovery" else "none"
        for ax, y in ((ax_z, 0.0), (ax_f, e.frequency_hz)):
            ax.plot([e.V], [y], "o", ms=8, mec=colour, mfc=face, mew=1.8, zorder=5)
        if e.event != "recovery":
            what = "flutter" if e.kind == "flutter" else "divergence"
            f = f", {e.frequency_hz:.2f} Hz" if e.kind == "flutter" else ""
            notes.append((e.V, f"{what} of {e.label}\n{e.V:.1f} m/s{f}", colour))
    if not notes:
        return
    lo = zlim[0]
    notes.sort()
    V0, V1 = ax_z.get_xlim() if xlim is None else xlim
    for i, (V, text, colour) in enumerate(notes):   # staggered on three levels by speed
        where = (V - V0) / (V1 - V0) if V1 > V0 else 0.5
        ha = "right" if where > 0.85 else "left" if where < 0.15 else "center"
        ax_z.annotate(text, xy=(V, 0.0), xytext=(V, -(0.15 + 0.27 * (i % 3)) * (0.0 - lo)),
                      textcoords="data", fontsize=7.5, color=colour, ha=ha, va="top",
                      arrowprops=dict(arrowstyle="-", color=colour, lw=0.7),
                      bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8))


def _zeta_limits(z: np.ndarray) -> tuple[float, float]:
    """ζ axis from the drawn (oscillatory) data, always with room below zero for the
    shaded unstable half and the notes."""
    finite = z[np.isfinite(z)]
    if finite.size == 0:
        return -0.1, 0.1
    lo, hi = min(float(finite.min()), 0.0), max(float(finite.max()), 0.0)
    span = max(hi - lo, 1e-3)
    lo = min(lo - 0.08 * span, -0.35 * span)
    return lo, hi + 0.08 * span
