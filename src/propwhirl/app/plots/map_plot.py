"""Figures of the critical speed over one or two parameters (:mod:`propwhirl.studies.sweeps`).

* :func:`critical_map` — filled contours of the critical speed over a parameter plane, the
  region where the critical instability is a divergence hatched and edged (so the critical kind
  reads at a glance), the region without instability in the speed range cross-hatched on grey,
  the design point (the model as given) marked with a star;
* :func:`critical_sweep` — the critical speed against one parameter, flutter and divergence
  points marked in their colours (Figure 7.4's), each change of the critical mode labelled, the
  design value drawn as a vertical line, points without instability marked at the top.
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from propwhirl import limits
from propwhirl import validate as v
from propwhirl.app.plots.canvas import DIVERGENCE_COLOUR, FLUTTER_COLOUR, finish, new_figure

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from propwhirl.studies.sweeps import CriticalMap

#: Hatch of the points whose critical instability is a divergence, and of those without any.
DIVERGENCE_HATCH = "//"
NONE_HATCH = "xx"
NONE_COLOUR = "0.85"


def _title(result: "CriticalMap", title: str | None) -> str:
    if title is not None:
        return limits.printable(title)
    name = limits.printable(result.model_name) or "model"
    return f"{name}: critical speed"


def critical_map(result: "CriticalMap", *, levels: int = 12, title: str | None = None,
                 path: str | Path | None = None) -> "Figure":
    """Filled contours of the critical speed [m/s] over the two parameters of `result` (a
    :func:`propwhirl.studies.sweeps.map2d`), at least 2 values each.

    Divergence-critical points are hatched (``//``) and their region edged with a dashed
    line; points with no instability in the speed range are grey, cross-hatched; the design
    point (both parameters as in the model, when known) is a white star.  `levels`: number of
    contour levels; written to `path` if given.

    Parameters
    ----------
    result : CriticalMap
        A study of two parameters (:func:`propwhirl.studies.map2d`).
    levels : int
        Number of contour levels.
    title : str, optional
        Figure title.
    path : str or Path, optional
        File to write.

    Returns
    -------
    matplotlib.figure.Figure
        The map (the parameters in their units on the axes) and its colour bar, the critical
        speed [m/s].

    Examples
    --------
    The isolated baseline propeller's pitch- and yaw-mount frequencies, 2 × 2 points:

    >>> from propwhirl.app.plots import critical_map
    >>> from propwhirl.studies import map2d
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> r = map2d(isolated_baseline_propeller(), ("propeller.f_theta", [6.0, 8.0]),
    ...           ("propeller.f_psi", [6.0, 8.0]), speeds=[100.0, 200.0, 300.0])
    >>> fig = critical_map(r)
    >>> [ax.get_xlabel() for ax in fig.axes][0], [ax.get_ylabel() for ax in fig.axes]
    ('propeller.f_theta [Hz]', ['propeller.f_psi [Hz]', 'critical speed [m/s]'])
    """
    if len(result.axes) != 2:
        raise v.InputError(f"a critical-speed map needs two parameters, the result has "
                           f"{len(result.axes)}: use critical_sweep for one")
    if min(result.shape) < 2:
        raise v.InputError(f"a critical-speed map needs at least 2 values of each parameter, "
                           f"got {result.shape[0]} x {result.shape[1]}")
    v.integer_at_least("levels", levels, 2)
    from matplotlib.patches import Patch
    from matplotlib.lines import Line2D

    ax1, ax2 = result.axes
    X, Y = result.grids()
    V = result.critical_speed
    kind = result.kind
    fig = new_figure(figsize=(8.0, 6.4))
    ax = fig.add_subplot(1, 1, 1)
    ax.set_facecolor(NONE_COLOUR)
    handles = []
    finite = np.isfinite(V)
    if finite.sum() >= 1:
        lo, hi = float(np.nanmin(V)), float(np.nanmax(V))
        if hi - lo < 1e-9 * max(1.0, abs(hi)):
            lo, hi = lo - 0.5, hi + 0.5
        cs = ax.contourf(X, Y, np.ma.masked_invalid(V), levels=np.linspace(lo, hi, levels + 1),
                         cmap="viridis")
        bar = fig.colorbar(cs, ax=ax)
        bar.set_label("critical speed [m/s]")
        ax.contour(X, Y, np.ma.masked_invalid(V), levels=cs.levels[1:-1:2], colors="k",
                   linewidths=0.4, alpha=0.5)
    none = (kind == "none").astype(float)
    if none.any():
        ax.contourf(X, Y, none, levels=[0.5, 1.5], colors="none", hatches=[NONE_HATCH])
        handles.append(Patch(facecolor=NONE_COLOUR, hatch=NONE_HATCH, edgecolor="0.4",
                             label="no instability in the speed range"))
    div = (kind == "divergence").astype(float)
    if div.any():
        ax.contourf(X, Y, div, levels=[0.5, 1.5], colors="none", hatches=[DIVERGENCE_HATCH])
        if not div.all():
            ax.contour(X, Y, div, levels=[0.5], colors=DIVERGENCE_COLOUR, linestyles="--",
                       linewidths=1.5)
        handles.append(Patch(facecolor="none", hatch=DIVERGENCE_HATCH, edgecolor=DIVERGENCE_COLOUR,
                             label="critical: divergence"))
    if (kind == "flutter").any():
        handles.append(Patch(facecolor="none", edgecolor="k", label="critical: flutter (plain)"))
    d1, d2 = ax1.design, ax2.design
    if d1 is not None and d2 is not None:
        ax.plot([d1], [d2], marker="*", markersize=16, color="white", markeredgecolor="k",
                linestyle="none", zorder=5)
        handles.append(Line2D([], [], marker="*", markersize=12, color="white",
                              markeredgecolor="k", linestyle="none",
                              label=f"design point ({d1:.4g}, {d2:.4g})"))
    ax.set_xlabel(limits.printable(ax1.label))
    ax.set_ylabel(limits.printable(ax2.label))
    ax.set_xlim(float(ax1.values.min()), float(ax1.values.max()))
    ax.set_ylim(float(ax2.values.min()), float(ax2.values.max()))
    ax.set_title(_title(result, title))
    if handles:
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.1),
                  ncol=min(3, len(handles)), fontsize=8, frameon=False)
    fig.tight_layout()
    return finish(fig, path)


def critical_sweep(result: "CriticalMap", *, title: str | None = None,
                   path: str | Path | None = None) -> "Figure":
    """The critical speed [m/s] against the one parameter of `result` (a
    :func:`propwhirl.studies.sweeps.sweep`): a line through the points, flutter points red,
    divergence points green, the critical mode named where it changes, the design value a
    dotted vertical line, points without instability as grey crosses at the top.  Written to
    `path` if given.

    Parameters
    ----------
    result : CriticalMap
        A study of one parameter (:func:`propwhirl.studies.sweep`).
    title : str, optional
        Figure title.
    path : str or Path, optional
        File to write.

    Returns
    -------
    matplotlib.figure.Figure
        One axes: the critical speed [m/s] against the parameter [its unit].

    Examples
    --------
    >>> from propwhirl.app.plots import critical_sweep
    >>> from propwhirl.studies import sweep
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> r = sweep(isolated_baseline_propeller(), "propeller.f_psi", [6.0, 7.0, 8.0],
    ...           speeds=[100.0, 200.0, 300.0])
    >>> ax = critical_sweep(r).axes[0]
    >>> ax.get_xlabel(), ax.get_ylabel()
    ('propeller.f_psi [Hz]', 'critical speed [m/s]')
    """
    if len(result.axes) != 1:
        raise v.InputError(f"a critical-speed sweep plot needs one parameter, the result has "
                           f"{len(result.axes)}: use critical_map for two")
    axis = result.axes[0]
    x = axis.values
    V = result.critical_speed
    kind = result.kind
    modes = np.asarray(result.columns["critical_mode"], dtype=object)
    fig = new_figure(figsize=(8.0, 5.0))
    ax = fig.add_subplot(1, 1, 1)
    ax.plot(x, V, color="0.3", linewidth=1.2, label="critical speed")
    for k, colour, marker in (("flutter", FLUTTER_COLOUR, "o"), ("divergence", DIVERGENCE_COLOUR, "s")):
        sel = kind == k
        if sel.any():
            ax.plot(x[sel], V[sel], linestyle="none", marker=marker, color=colour,
                    label=f"critical: {k}")
    finite = np.isfinite(V)
    top = float(np.nanmax(V)) * 1.08 if finite.any() else 1.0
    none = kind == "none"
    if none.any():
        ax.plot(x[none], np.full(int(none.sum()), top), linestyle="none", marker="x",
                color="0.5", label="no instability in the speed range")
    last = None
    for xi, Vi, m, k in zip(x, V, modes, kind):   # name the mode where it (or its kind) changes
        if np.isfinite(Vi) and (m, k) != last:
            ax.annotate(limits.printable(str(m)), (xi, Vi), textcoords="offset points",
                        xytext=(4, 6), fontsize=8)
        last = (m, k) if np.isfinite(Vi) else last
    if axis.design is not None:
        ax.axvline(axis.design, color="k", linestyle=":", linewidth=1.0,
                   label=f"design value {axis.design:.4g}")
    ax.set_xlabel(limits.printable(axis.label))
    ax.set_ylabel("critical speed [m/s]")
    ax.set_title(_title(result, title))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    return finish(fig, path)
