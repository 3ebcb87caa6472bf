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
from propwhirl.app.plots.canvas import DIVERGENCE_COLOUR, FLUTTER_COLOUR, finish, new_figure

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from propwhirl.studies.boundary import Boundary, GridMap
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
    """
    bs = [boundaries] if not isinstance(boundaries, (list, tuple)) else list(boundaries)
    if not bs:
        raise v.InputError("boundaries is empty: give at least one Boundary")
    first = bs[0]
    fig = new_figure(figsize=(7.5, 6.0), layout="constrained")
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
            ax.plot([], [], "--", color="dimgrey", lw=1.5, label="boundary read off the grid "
                    "(linear interpolation)")
    for i, b in enumerate(bs):
        c = _CURVE_COLOURS[i % len(_CURVE_COLOURS)]
        style = dict(lw=4.0, ms=6) if i == 0 else dict(lw=1.5, ms=3.0)  # coinciding curves stay visible
        for k, pts in enumerate(b.curves):
            ax.plot(pts[:, 0], pts[:, 1], "-o", color=c, **style,
                    label=f"{_curve_label(b)} ({b.evaluations} {b.evaluation_name})" if k == 0 else None)
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
    if grid is not None and first.kind == "neutral-stability":
        X, Y = np.meshgrid(grid.x, grid.y, indexing="ij")
        for side, colour, name in ((grid.values > 0, "darkred", "unstable"),
                                   (grid.values < 0, "navy", "stable")):
            if side.any():
                # the grid point of that side closest to the side's centroid
                cx, cy = X[side].mean(), Y[side].mean()
                k = int(np.argmin(np.hypot(X[side] - cx, Y[side] - cy)))
                ax.text(X[side][k], Y[side][k], name, ha="center", va="center", fontsize=12,
                        color=colour, weight="bold")
    ax.legend(fontsize=8, loc="lower right", framealpha=0.9)
    ax.grid(True, alpha=0.3)
    ax.set_title(title or f"{first.model_name}: stability boundary", fontsize=10)
    return finish(fig, path)


def clearance_plot(result: "Clearance", *, title: str | None = None,
                   path: str | Path | None = None) -> "Figure":
    """The margin V / (factor · V_D) − 1 [%] of every instability in the analysed range as
    horizontal bars (flutter red, divergence green, events the convention leaves out hatched),
    the requirement at 0."""
    fig = new_figure(figsize=(8.0, 1.6 + 0.45 * max(len(result.margins), 1)), layout="constrained")
    ax = fig.subplots()
    names = [f"{m.kind} {m.event} of {m.mode} ({m.V:.1f} m/s)" for m in result.margins]
    vals = [100 * m.margin for m in result.margins]
    cols = [FLUTTER_COLOUR if m.kind == "flutter" else DIVERGENCE_COLOUR for m in result.margins]
    y = np.arange(len(vals))
    bars = ax.barh(y, vals, color=cols, alpha=0.8)
    for bar, m in zip(bars, result.margins):
        if not m.counted:
            bar.set_hatch("//")
            bar.set_alpha(0.35)
    ax.set_yticks(y, names, fontsize=8)
    ax.invert_yaxis()
    ax.axvline(0.0, color="black", lw=1.5)
    ax.set_xlabel(f"margin V / ({result.factor:g} V_D) - 1 [%]   (V_D = {result.V_D:g} m/s)")
    verdict = "cleared" if result.cleared else "NOT cleared"
    ax.set_title(title or f"{result.model_name}\n{verdict} to {result.factor:g} V_D = "
                 f"{result.V_required:.1f} m/s", fontsize=10)
    ax.grid(True, axis="x", alpha=0.3)
    if not result.margins:
        ax.text(0.5, 0.5, "no instability in the analysed range", transform=ax.transAxes,
                ha="center")
    return finish(fig, path)
