"""The figures of a campaign report (:mod:`propwhirl.app.report`), drawn from what a campaign's
result keeps of each analysis (:class:`~propwhirl.studies.campaign_result.PointPlot`), so a
report can be drawn again from ``campaign.json`` without analysing anything:

* :func:`point_vgf` — the V-g-f (drawn by :func:`propwhirl.app.plots.vgf_plot.vgf_figure`,
  as every V-g-f) of the modes of interest at the analysed speeds (the sweep's nodes,
  marked; cubic Hermite curves between them from the exact slopes, :func:`hermite`), the
  instabilities marked and labelled, V_D and the required speed factor · V_D drawn as
  vertical lines, the damping requirement g = 2ζ ≥ g_min as a horizontal line up to V_D;
* :func:`point_mode_shape` — the critical mode: the wing's h and α along the span (Re x̂ and
  the envelope ±|x̂|) and one θ–ψ orbit per propeller;
* :func:`mesh_plot` — the wing's nodes along the span and the propeller stations;
* :func:`wing_properties_plot` — EI, GJ and the mass per length along the span.
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from propwhirl.analysis.naming import is_lag, mode_family
from propwhirl.app.plots.canvas import finish, new_figure
from propwhirl.app.plots import vgf_plot
from propwhirl.app.plots.vgf_plot import (HERMITE_POINTS, VgfCurves, VgfEvent, VgfRequirements,
                                          damping_fall_of, emphasised, hermite_columns,
                                          hermite_step)

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from propwhirl.studies.campaign_result import PointPlot, PointRow


def point_vgf(row: "PointRow", min_damping_g: float | None = None, *,
              title: str | None = None, path: str | Path | None = None) -> "Figure":
    """V-g-f of one (case, envelope point) of a campaign with its requirements drawn, by
    :func:`propwhirl.app.plots.vgf_plot.vgf_figure` (every V-g-f's drawing: family colours,
    the ζ axis around the region that matters, the instabilities marked and labelled).

    `row`: a :class:`~propwhirl.studies.campaign_result.PointRow` with its ``plot``: its modes
    of interest, bold and named in the legend as :func:`propwhirl.app.plots.vgf_plot.vgf`
    emphasises them (an instability, or a damping that falls below
    :data:`~propwhirl.app.plots.vgf_plot.DAMPING_MARGIN`; an aerodynamic lag root thin),
    coloured by family from the name (:func:`propwhirl.analysis.naming.mode_family`: a saved
    point keeps no content, so a wing mode is "wing bending"), cubic Hermite curves
    (:func:`hermite`) through the analysed speeds (dots); V_D, the required speed, the
    critical speed and `min_damping_g`, the campaign's damping requirement (g = 2ζ, drawn
    as ζ = g/2 up to V_D; None for none)."""
    p: "PointPlot" = row.plot
    V = np.asarray(p.V, dtype=float)
    osc = np.asarray(p.oscillatory, dtype=bool)
    Vs, zeta = hermite_columns(V, p.zeta, p.dzeta_dV, osc)
    _, freq = hermite_columns(V, p.frequency_hz, p.dfrequency_dV, osc)
    nodes = (V, np.where(osc, p.zeta, np.nan), np.where(osc, p.frequency_hz, np.nan))
    events = [VgfEvent(kind, event, mode, float(Ve), float(fe))
              for Ve, fe, kind, event, mode in p.events]
    bold = emphasised(p.modes, damping_fall_of(nodes[1]), events, (float(V[0]), float(V[-1])))
    curves = VgfCurves(V=Vs, zeta=zeta, frequency_hz=freq, labels=tuple(p.modes),
                       names=tuple(p.modes), families=tuple(mode_family(m) for m in p.modes),
                       bold=tuple(b and not is_lag(m) for b, m in zip(bold, p.modes)),
                       nodes=nodes)
    req = VgfRequirements(row.V_D, row.V_required, min_damping_g, row.critical_speed,
                          row.kind)
    fig = vgf_plot.vgf_figure(curves, events, requirements=req, label_least_damped=False,
                              xlabel="true airspeed V [m/s]", figsize=(9.0, 5.6),
                              title=title or _wrap(f"{row.case} at {row.altitude_m:g} m: V-g-f"),
                              zeta_limits=deciding_band(V, nodes[1], row.V_required,
                                                        min_damping_g))
    return finish(fig, path)


#: The band that decides never reaches below this ζ [-] above zero (a whirl mode with the
#: mounts' structural damping g = 0.02 sits at ζ = 0.01: legible in it).
BAND_TOP = 0.05


def deciding_band(V: np.ndarray, zeta: np.ndarray, V_required: float,
                  min_damping_g: float | None) -> tuple[float, float]:
    """The ζ axis (lo, hi) of a campaign's V-g-f on the band that decides (issue 35, item 3):
    up to the greatest of :data:`BAND_TOP`, three times the damping requirement ζ = g/2 and
    1.15 × the least damped mode's highest ζ up to the required speed (that mode's whole
    curve), at most :data:`~propwhirl.app.plots.vgf_plot.ZETA_TOP`; below zero to half of it
    (at least :data:`~propwhirl.app.plots.vgf_plot.ZETA_BOTTOM`).  A mode damped far more —
    one wing mode at ζ = 0.2 — leaves it, marked by a triangle, instead of squeezing the
    modes that decide into a thin band.  `zeta` (T, n) NaN where a mode is not oscillatory;
    V (T,) [m/s]."""
    z = np.where((np.asarray(V, dtype=float) <= V_required * (1 + 1e-12))[:, None],
                 np.asarray(zeta, dtype=float), np.nan)
    peaks = np.nanmax(np.where(np.isfinite(z), z, -np.inf), axis=0) if z.size else np.array([])
    peaks = peaks[np.isfinite(peaks)]
    least = float(peaks.min()) if peaks.size else 0.0
    top = max(BAND_TOP, 1.5 * (min_damping_g or 0.0), 1.15 * least)
    top = min(top, vgf_plot.ZETA_TOP)
    return min(vgf_plot.ZETA_BOTTOM, -0.5 * top), top


def hermite(V: np.ndarray, y: np.ndarray, dy: np.ndarray, valid: np.ndarray,
            n: int = HERMITE_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """The cubic Hermite curve through (V, y) with slopes dy [per m/s], `n` points per step
    where both ends are `valid` (:func:`hermite_columns` of the one curve: the engine's model
    of a step, :func:`propwhirl.engine.hermite.hermite_coeffs`); one NaN between (a gap in the
    drawn line).  A step whose cubic leaves the band of its end values widened by their
    difference and a quarter of the curve's whole range is drawn straight: there the slope
    is near-singular (a branch point) and the cubic would invent a peak."""
    V, y, dy, valid = (np.asarray(x) for x in (V, y, dy, valid))
    if len(V) < 2:
        return V[valid], y[valid]
    grid, curve = hermite_columns(V, y[:, None], dy[:, None], valid[:, None], n)
    steps = range(len(V) - 1)
    xs = [grid[j * n:(j + 1) * n] if valid[j] and valid[j + 1] else [np.nan] for j in steps]
    ys = [curve[j * n:(j + 1) * n, 0] if valid[j] and valid[j + 1] else [np.nan] for j in steps]
    return np.concatenate(xs), np.concatenate(ys)


def point_mode_shape(row: "PointRow", *, title: str | None = None,
                     path: str | Path | None = None) -> "Figure | None":
    """The critical mode of one (case, envelope point) (None when it has none): the wing's
    h and α [normalised] along the span y [m] and a θ–ψ orbit per propeller (numbered from 1)
    with its share of the mode's kinetic energy and its whirl sense."""
    sh = None if row.plot is None else row.plot.shape
    if sh is None:
        return None
    props = sh["propellers"]
    ncol = min(4, max(len(props), 1))
    nrow = -(-len(props) // ncol) if props else 0
    fig = new_figure(figsize=(max(2.6 * ncol, 8.0), 2.6 + 2.3 * nrow), layout="constrained")
    grid = fig.add_gridspec(1 + nrow, ncol, height_ratios=[2.2] + [2.0] * nrow)
    ax = fig.add_subplot(grid[0, :])
    y = np.asarray(sh["y"], dtype=float)
    ax_a = ax.twinx()
    if not y.size:          # no wing node DOFs (a modal model: its coordinates are modes)
        ax.text(0.5, 0.5, "the wing's h and α are not drawn: the model's coordinates are "
                "its modes", transform=ax.transAxes, ha="center", va="center", fontsize=8)
    for axis, key, name, colour in ((ax, "h", "plunge h", "C0"), (ax_a, "alpha", "twist α", "C3")):
        if not y.size:
            break
        vals = np.asarray(sh[key], dtype=complex)
        env = np.abs(vals)
        axis.fill_between(y, -env, env, color=colour, alpha=0.12, lw=0)
        axis.plot(y, vals.real, "-", color=colour, lw=1.6, label=f"{name}: Re x̂")
        axis.set_ylabel(f"{name} [normalised]", color=colour)
        top = float(env.max()) or 1.0
        axis.set_ylim(-1.15 * top, 1.15 * top)
    for number, yp, _t, _p in props:
        if yp is not None:
            ax.axvline(yp, color="0.5", lw=0.8, ls="--")
            ax.annotate(f"P{number}", (yp, 1.0), xycoords=("data", "axes fraction"),
                        xytext=(0, 2), textcoords="offset points", ha="center", va="bottom",
                        fontsize=8)
    if y.size:
        ax.set_xlim(0.0, float(y[-1]) * 1.01 or 1.0)
    ax.set_xlabel("spanwise position y [m]")
    ax.grid(True, alpha=0.3)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax_a.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=7.5, loc="lower left", ncol=2)
    shares = {n: (s, w) for n, s, w in row.propeller_shares}
    lam = complex(sh["eigenvalue"])
    sign = 1.0 if lam.imag >= 0 else -1.0
    phase = np.exp(1j * sign * np.linspace(0.0, 2.0 * np.pi, 121))
    paths = [((complex(t) * phase).real, (complex(q) * phase).real) for _n, _y, t, q in props]
    extent = 1.1 * max((float(np.abs(np.r_[a, b]).max()) for a, b in paths), default=1.0) or 1.0
    for i, ((number, yp, _t, _q), (a, b)) in enumerate(zip(props, paths)):
        axp = fig.add_subplot(grid[1 + i // ncol, i % ncol])
        axp.plot(a, b, "-", color="C2", lw=1.5)
        axp.plot([a[0]], [b[0]], "o", color="C2", ms=4)
        axp.annotate("", xy=(a[9], b[9]), xytext=(a[6], b[6]),
                     arrowprops=dict(arrowstyle="->", color="C2", lw=1.5))
        s, w = shares.get(number, (None, ""))
        where = "" if yp is None else f" (y = {yp:.3g} m)"
        extra = ("" if s is None else f"\n{100 * s:.0f} % of the energy") + (f", {w} whirl"
                                                                           if w else "")
        axp.set_title(f"propeller {number}{where}{extra}", fontsize=8)
        axp.axhline(0.0, color="0.3", lw=0.6)
        axp.axvline(0.0, color="0.3", lw=0.6)
        axp.set_xlim(-extent, extent)
        axp.set_ylim(-extent, extent)
        axp.set_aspect("equal", adjustable="box")
        axp.tick_params(labelsize=7)
        axp.set_xlabel("θ (pitch)", fontsize=8)
        axp.set_ylabel("ψ (yaw)", fontsize=8)
    f_hz = abs(lam.imag) / (2.0 * np.pi)
    fig.suptitle(title or _wrap(f"{row.case} at {row.altitude_m:g} m: critical mode {row.mode} "
                                f"({row.kind} {row.event})")
                 + f"\nV = {sh['V']:.2f} m/s, f = {f_hz:.3f} Hz", fontsize=10)
    return finish(fig, path)


def mesh_plot(node_y: Sequence[float], propellers: Sequence[tuple[int, float | None]], *,
              title: str = "", path: str | Path | None = None) -> "Figure":
    """The wing's mesh: its nodes along the span y [m] (root clamped at 0) and the propeller
    stations, `propellers` as (number from 1, y [m] or None)."""
    y = np.asarray(node_y, dtype=float)
    fig = new_figure(figsize=(9.0, 1.9), layout="constrained")
    ax = fig.add_subplot()
    ax.plot(y, np.zeros_like(y), "-", color="0.4", lw=2.0)
    ax.plot(y, np.zeros_like(y), "|", color="0.1", ms=14, mew=1.2,
            label=f"{max(y.size - 1, 0)} elements, {y.size} nodes")
    ax.plot([0.0], [0.0], "s", color="0.1", ms=8, label="clamped root")
    for number, yp in propellers:
        if yp is not None:
            ax.plot([yp], [0.0], "o", ms=12, mfc="none", mec="C3", mew=2.0)
            ax.annotate(f"P{number}", (yp, 0.0), xytext=(0, 10), textcoords="offset points",
                        ha="center", fontsize=9, color="C3")
    ax.set_yticks([])
    ax.set_ylim(-1.0, 1.0)
    ax.set_xlabel("spanwise position y [m]")
    ax.legend(fontsize=8, loc="lower right")
    if title:
        ax.set_title(title, fontsize=10)
    return finish(fig, path)


def wing_properties_plot(y: Sequence[float], m: Sequence[float], EI: Sequence[float],
                         GJ: Sequence[float], propellers: Sequence[tuple[int, float | None]],
                         *, path: str | Path | None = None) -> "Figure":
    """The wing's structural data along the span y [m] (each element's value at its
    mid-span, drawn as steps over the element): EI and GJ [N m²] and the mass per length
    m [kg/m]; the propeller stations, `propellers` as (number from 1, y [m] or None)."""
    y = np.asarray(y, dtype=float)
    fig = new_figure(figsize=(9.0, 2.8), layout="constrained")
    ax_k, ax_m = fig.subplots(1, 2)
    ax_k.step(y, EI, where="mid", color="C0", lw=1.8, label="EI (bending)")
    ax_k.step(y, GJ, where="mid", color="C3", lw=1.8, label="GJ (torsion)")
    ax_k.set_ylabel("rigidity [N m²]")
    ax_k.set_yscale("log")
    ax_m.step(y, m, where="mid", color="0.2", lw=1.8, label="m (mass per length)")
    ax_m.set_ylabel("mass per length [kg/m]")
    ax_m.set_ylim(0.0, 1.15 * float(np.max(m)) if len(y) else 1.0)
    for ax in (ax_k, ax_m):
        for number, yp in propellers:
            if yp is not None:
                ax.axvline(yp, color="C2", lw=0.8, ls="--")
                ax.annotate(f"P{number}", (yp, 1.0), xycoords=("data", "axes fraction"),
                            xytext=(0, 2), textcoords="offset points", ha="center",
                            va="bottom", fontsize=8, color="C2")
        ax.set_xlabel("spanwise position y [m]")
        ax.set_xlim(0.0, float(y[-1]) * 1.02 if len(y) else 1.0)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="lower left")
    return finish(fig, path)


def _wrap(text: str, width: int = 90) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width)) or text


def svg_bytes(fig: Any) -> bytes:
    """The figure as SVG bytes (a vector image for a data: URI; text as paths, so it looks
    the same without the fonts)."""
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="svg", metadata={"Date": None})
    return buf.getvalue()


def png_bytes(fig: Any, dpi: int = 80) -> bytes:
    """The figure as PNG bytes (for a data: URI)."""
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return buf.getvalue()
