"""The stability diagram of a parameter plane and the clearance margins.

:func:`boundary_plot` — traced boundaries (:mod:`propwhirl.studies.boundary`) over the filled
contours of a coarse grid map of the same plane (its own zero contour dashed, for comparison),
the start points and the design point marked, the unstable side named.
:func:`clearance_plot` — the margin of every instability against factor · V_D
(:mod:`propwhirl.studies.clearance`).
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Sequence

import numpy as np

from propwhirl import validate as v
from propwhirl.app.plots.canvas import finish, new_figure
from propwhirl.app.plots.layout import wrap

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from propwhirl.studies.boundary import Boundary, GridMap
    from propwhirl.analysis.stability import ModelAnalysis
    from propwhirl.studies.clearance import Clearance

_CURVE_COLOURS = ("black", "darkorange", "purple", "teal")


def _curve_label(b: "Boundary") -> str:
    if b.kind == "neutral-stability":
        what = "flutter modes" if b.settings.get("oscillatory") else "least stable mode"
        return f"neutral stability at V = {b.speed:g} m/s ({what}), traced"
    return f"V_crit = {b.speed:g} m/s, traced"


def boundary_plot(boundaries: "Boundary | Sequence[Boundary]", grid: "GridMap | None" = None, *,
                  design: Sequence[float] | None = None, title: str | None = None,
                  path: str | Path | None = None) -> "Figure":
    """Traced boundaries in their parameter plane over a grid map.

    boundaries: one or more :class:`~propwhirl.studies.boundary.Boundary` of one plane;
    grid: a :class:`~propwhirl.studies.boundary.GridMap` of the first boundary's level function
    (:func:`~propwhirl.studies.boundary.level_of`): filled contours (max Re λ [1/s] for a
    neutral curve, V_crit [m/s] for a contour) and its zero contour dashed;
    design: the model's point (p₁, p₂), marked with a star.

    Parameters
    ----------
    boundaries : Boundary or sequence of Boundary
        Traced boundaries of one plane (:func:`propwhirl.studies.boundary.neutral_curve`,
        :func:`~propwhirl.studies.boundary.speed_contour`).
    grid : GridMap, optional
        The first boundary's level function on a grid of the plane.
    design : sequence of float, optional
        The model's point (p₁, p₂) [the parameters' units].
    title : str, optional
        Figure title.
    path : str or Path, optional
        File to write.

    Returns
    -------
    matplotlib.figure.Figure
        The plane (the parameters in their units) and, with `grid`, a colour bar.

    Examples
    --------
    Where the isolated baseline propeller is neutrally stable at 200 m/s in the plane of its
    mount frequencies [Hz], over a 5 × 5 grid of max Re λ:

    >>> from propwhirl.app.plots import boundary_plot
    >>> from propwhirl.studies.boundary import grid_map, level_of, neutral_curve
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> model = isolated_baseline_propeller()
    >>> plane = ("propeller.f_theta", "propeller.f_psi"), (4.0, 4.0), (10.0, 10.0)
    >>> b = neutral_curve(model, *plane, V=200.0)
    >>> grid = grid_map(level_of(b, model), *plane[1:], n=5)
    >>> fig = boundary_plot(b, grid, design=(7.0, 7.0))
    >>> fig.axes[0].get_xlabel(), fig.axes[0].get_ylabel()
    ('propeller.f_theta [Hz]', 'propeller.f_psi [Hz]')
    """
    bs = [boundaries] if not isinstance(boundaries, (list, tuple)) else list(boundaries)
    if not bs:
        raise v.InputError("boundaries is empty: give at least one Boundary")
    first = bs[0]
    fig = new_figure(figsize=(7.5, 8.0), layout="constrained")
    ax = fig.subplots()
    if grid is not None:
        X, Y = np.meshgrid(grid.x, grid.y, indexing="ij")
        if first.kind == "neutral-stability":
            from matplotlib.colors import TwoSlopeNorm

            z = grid.values
            lo_z, hi_z = float(np.min(z)), float(np.max(z))
            norm = TwoSlopeNorm(0.0, min(lo_z, -1e-9), max(hi_z, 1e-9))
            cf = ax.contourf(X, Y, z, levels=np.unique(np.concatenate(
                [np.linspace(min(lo_z, 0.0), 0.0, 9), np.linspace(0.0, max(hi_z, 0.0), 12)])),
                cmap="RdBu_r", norm=norm)
            label = f"max Re λ at V = {first.speed:g} m/s [1/s] (grid {len(grid.x)} x {len(grid.y)})"
        else:
            z = grid.values + first.speed
            cf = ax.contourf(X, Y, z, levels=16, cmap="viridis")
            label = f"V_crit [m/s] (grid {len(grid.x)} x {len(grid.y)})"
        fig.colorbar(cf, ax=ax, label=label)
        if np.nanmin(grid.values) < 0 < np.nanmax(grid.values):
            ax.contour(X, Y, grid.values, levels=[0.0], colors="dimgrey", linestyles="--",
                       linewidths=1.5)
            what = ("max Re λ = 0" if first.kind == "neutral-stability"
                    else f"V_crit = {first.speed:g} m/s")
            ax.plot([], [], "--", color="dimgrey", lw=1.5, label=f"{what} read off the grid "
                    "(linear interpolation: within a cell of the traced curve)")
        dx, dy = float(grid.x[1] - grid.x[0]), float(grid.y[1] - grid.y[0])
        u1, u2 = (f" {u}" if u else "" for u in first.units)
        fig.supxlabel(wrap(
            f"Colours: the level on a {len(grid.x)} x {len(grid.y)} grid (cells {dx:.3g}{u1} x "
            f"{dy:.3g}{u2}), smoothed between its points; the pale band is where it is near "
            "zero, the grey dashed line its zero read off the grid — both are the grid's "
            "reading, within a cell of the boundary. The thick line is the boundary traced by "
            "continuation, to its tolerance; each branch numbered.", 110), fontsize=7,
            color="0.25")
    for i, b in enumerate(bs):
        c = _CURVE_COLOURS[i % len(_CURVE_COLOURS)]
        style = dict(lw=4.0, ms=6) if i == 0 else dict(lw=1.5, ms=3.0)  # coinciding curves stay visible
        for k, pts in enumerate(b.curves):
            closed = k < len(b.closed) and bool(b.closed[k]) and len(pts) > 2
            pts = np.vstack([pts, pts[:1]]) if closed else pts       # a closed curve drawn closed
            n = len(b.curves)
            ax.plot(pts[:, 0], pts[:, 1], "-o", color=c, **style,
                    label=f"{_curve_label(b)}: {n} branch{'es' if n > 1 else ''} "
                    f"({b.evaluations} {b.evaluation_name})" if k == 0 else None)
            if n > 1 and i == 0:             # each branch numbered, as the text names it
                mid = pts[len(pts) // 2]
                ax.annotate(str(k + 1), mid, xytext=(6, 6), textcoords="offset points",
                            fontsize=10, weight="bold", color=c,
                            bbox=dict(boxstyle="circle,pad=0.2", fc="white", ec=c))
        if len(b.starts):
            ax.plot(b.starts[:, 0], b.starts[:, 1], "s", color=c, mfc="none", ms=9,
                    label="start (bracketing search)" if i == 0 else None)
    if design is not None:
        ax.plot([design[0]], [design[1]], "*", color="gold", mec="black", ms=16, label="design point",
                zorder=5)
    ax.set_xlim(first.lower[0], first.upper[0])
    ax.set_ylim(first.lower[1], first.upper[1])
    ax.set_xlabel(f"{first.parameters[0]} [{first.units[0]}]" if first.units[0] else first.parameters[0])
    ax.set_ylabel(f"{first.parameters[1]} [{first.units[1]}]" if first.units[1] else first.parameters[1])
    if grid is not None:
        _sides(ax, grid, first)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.1), framealpha=0.9)
    ax.grid(True, alpha=0.3)
    ax.set_title(title or f"{first.model_name}: stability boundary", fontsize=10)
    return finish(fig, path)


def _unstable(grid: "GridMap", b: "Boundary") -> np.ndarray:
    """Where the grid's level function says unstable: max Re λ > 0 (a neutral curve) or
    V_crit below the boundary's speed (a V_crit contour: the level is V_crit − speed)."""
    return grid.values > 0 if b.kind == "neutral-stability" else grid.values < 0


def _sides(ax, grid: "GridMap", b: "Boundary") -> None:
    """The unstable side hatched over the filled contours (in the legend "unstable side"),
    each side named at its grid point nearest its centroid."""
    X, Y = np.meshgrid(grid.x, grid.y, indexing="ij")
    bad = _unstable(grid, b)
    if bad.any() and (~bad).any():
        ax.contourf(X, Y, bad.astype(float), levels=[0.5, 1.5], colors="none",
                    hatches=["//"])
    if bad.any():
        ax.fill([], [], facecolor="none", edgecolor="black", hatch="//", label="unstable side"
                + ("" if b.kind == "neutral-stability" else f" (V_crit < {b.speed:g} m/s)"))
    for side, colour, name in ((bad, "darkred", "unstable"), (~bad, "navy", "stable")):
        if side.any():
            cx, cy = X[side].mean(), Y[side].mean()
            k = int(np.argmin(np.hypot(X[side] - cx, Y[side] - cy)))
            ax.text(X[side][k], Y[side][k], name, ha="center", va="center", fontsize=12,
                    color=colour, weight="bold",
                    bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="none", alpha=0.8))


#: bar colours of the clearance chart: the requirement met or not
PASS_COLOUR = "tab:green"
FAIL_COLOUR = "tab:red"


def _propellers_of(margin, analysis) -> str:
    """'propeller 6' / 'propellers 4, 2, 1': the propellers of the analysis's event of
    `margin` holding at least half the largest propeller share (at most three, largest
    first); "" without the analysis, the event, its participation or a propeller share of
    5 % or more."""
    if analysis is None:
        return ""
    for e in analysis.events:
        if (e.label, e.kind, e.event) == (margin.mode, margin.kind, margin.event) and \
                abs(e.V - margin.V) <= 1e-6 * max(1.0, abs(margin.V)):
            p = e.participation
            if p is None or not p.propellers:
                return ""
            shares = sorted(p.propellers, key=lambda s: -s.share)
            if shares[0].share < 0.05:
                return ""
            who = [s.propeller for s in shares if s.share >= 0.5 * shares[0].share][:3]
            return ("propeller " if len(who) == 1 else "propellers ") + ", ".join(map(str, who))
    return ""


def clearance_plot(result: "Clearance", *, analysis: "ModelAnalysis | None" = None,
                   title: str | None = None,
                   path: str | Path | None = None) -> "Figure":
    """The margin V / (factor · V_D) − 1 [%] of every instability in the analysed range as
    horizontal bars coloured by the verdict (:data:`PASS_COLOUR` where the margin is ≥ 0,
    :data:`FAIL_COLOUR` where it is negative; events the convention leaves out hatched and
    pale), each named by its kind, event, mode and speed and — given the `analysis` the
    clearance was computed from — the propellers that lead the whirl at the event ("propellers
    4, 2, 1 leading": those with at least half the largest share); the requirement at 0.

    Parameters
    ----------
    result : Clearance
        A clearance (:func:`propwhirl.studies.clearance.clearance`).
    analysis : ModelAnalysis, optional
        The analysis the clearance was computed from (the leading propellers).
    title : str, optional
        Figure title.
    path : str or Path, optional
        File to write.

    Returns
    -------
    matplotlib.figure.Figure
        One axes: a bar per instability, its margin [%].

    Examples
    --------
    >>> from propwhirl.app.plots import clearance_plot
    >>> from propwhirl.studies.clearance import clearance
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> c = clearance(isolated_baseline_propeller(), 180.0, minimum=False,
    ...               speeds=[100.0, 200.0, 250.0])
    >>> clearance_plot(c).axes[0].get_xlabel()
    'margin V / (1.15 V_D) - 1 [%]   (V_D = 180 m/s)'
    """
    from matplotlib.patches import Patch

    fig = new_figure(figsize=(8.5, 1.8 + 0.5 * max(len(result.margins), 1)), layout="constrained")
    ax = fig.subplots()
    names = []
    for m in result.margins:
        who = _propellers_of(m, analysis)
        names.append(f"{m.kind} {m.event} of {m.mode} ({m.V:.1f} m/s)"
                     + (f"\n{who} leading" if who else ""))
    vals = [100 * m.margin for m in result.margins]
    cols = [PASS_COLOUR if m.margin >= 0 else FAIL_COLOUR for m in result.margins]
    y = np.arange(len(vals))
    bars = ax.barh(y, vals, color=cols, alpha=0.85)
    for bar, m in zip(bars, result.margins):
        if not m.counted:
            bar.set_hatch("//")
            bar.set_alpha(0.35)
    ax.set_yticks(y, names, fontsize=8)
    ax.invert_yaxis()
    ax.axvline(0.0, color="black", lw=1.5)
    ax.set_xlabel(f"margin V / ({result.factor:g} V_D) - 1 [%]   (V_D = {result.V_D:g} m/s)")
    verdict = "cleared" if result.cleared else "NOT cleared"
    ax.set_title(title or f"{wrap(result.model_name, 60)}\n{verdict} to {result.factor:g} V_D = "
                 f"{result.V_required:.1f} m/s", fontsize=10)
    ax.grid(True, axis="x", alpha=0.3)
    if result.margins:
        handles = [Patch(color=PASS_COLOUR, alpha=0.85, label="margin met"),
                   Patch(color=FAIL_COLOUR, alpha=0.85, label="margin not met")]
        if not all(m.counted for m in result.margins):
            handles.append(Patch(facecolor="0.8", hatch="//", label="not counted (convention)"))
        ax.legend(handles=handles, fontsize=8, loc="best")
    if not result.margins:
        ax.text(0.5, 0.5, "no instability in the analysed range", transform=ax.transAxes,
                ha="center")
    return finish(fig, path)
