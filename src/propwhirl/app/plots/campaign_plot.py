"""The figures of a campaign report (:mod:`propwhirl.app.report`), drawn from what a campaign's
result keeps of each analysis (:class:`~propwhirl.studies.campaign_result.PointPlot`), so a
report can be drawn again from ``campaign.json`` without analysing anything:

* :func:`point_vgf` — ζ and f [Hz] against V [m/s] of the modes of interest at the analysed
  speeds (the sweep's nodes, marked; cubic Hermite curves between them from the exact
  slopes, :func:`hermite`), the instabilities marked (flutter red, divergence green,
  as :mod:`~propwhirl.app.plots.vgf_plot`), V_D and the required speed factor · V_D drawn as
  vertical lines, the damping requirement g = 2ζ ≥ g_min as a horizontal line up to V_D;
* :func:`point_mode_shape` — the critical mode: the wing's h and α along the span (Re x̂ and
  the envelope ±|x̂|) and one θ–ψ orbit per propeller;
* :func:`mesh_plot` — the wing's nodes along the span and the propeller stations.
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from propwhirl.app.plots.canvas import (DIVERGENCE_COLOUR, FLUTTER_COLOUR, colours, finish,
                                        new_figure)
from propwhirl.engine.hermite import hermite_coeffs, hermite_eval

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from propwhirl.studies.campaign_result import PointPlot, PointRow

#: colour of the V_D, required-speed and damping-requirement lines
REQUIREMENT_COLOUR = "0.15"
#: the V-g-f's ζ axis spans at most ±this [-] (beyond: the curve leaves the axes)
ZETA_LIMIT = 0.4
#: points of the drawn curve per analysed speed step
HERMITE_POINTS = 12


def point_vgf(row: "PointRow", min_damping_g: float | None = None, *,
              title: str | None = None, path: str | Path | None = None) -> "Figure":
    """V-g-f of one (case, envelope point) of a campaign with its requirements drawn.

    `row`: a :class:`~propwhirl.studies.campaign_result.PointRow` with its ``plot``;
    `min_damping_g`: the campaign's damping requirement (g = 2ζ, drawn as ζ = g/2 up to V_D),
    None for none."""
    p: "PointPlot" = row.plot
    fig = new_figure(figsize=(9.0, 5.6), layout="constrained")
    ax_z, ax_f = fig.subplots(2, 1, sharex=True)
    V = p.V
    cmap = colours(len(p.modes))
    for k, (name, colour) in enumerate(zip(p.modes, cmap)):
        osc = p.oscillatory[:, k]
        for ax, y, dy in ((ax_z, p.zeta[:, k], p.dzeta_dV[:, k]),
                          (ax_f, p.frequency_hz[:, k], p.dfrequency_dV[:, k])):
            ax.plot(*hermite(V, y, dy, osc), "-", color=colour, lw=1.4,
                    label=name if ax is ax_z else None)
            ax.plot(V[osc], y[osc], ".", ms=3, color=colour)
    z = np.where(p.oscillatory, p.zeta, np.nan)
    finite = z[np.isfinite(z)]
    # the axis from the data, clipped at ZETA_LIMIT: a root near the real axis (|ζ| → 1) would
    # flatten the curves that decide the clearance
    lo = max(min(float(finite.min()) if finite.size else 0.0, 0.0), -ZETA_LIMIT)
    hi = min(max(float(finite.max()) if finite.size else 0.1, 0.0), ZETA_LIMIT)
    if min_damping_g is not None:
        hi = max(hi, 0.5 * min_damping_g)
    span = max(hi - lo, 1e-3)
    lo, hi = min(lo - 0.08 * span, -0.2 * span), hi + 0.08 * span
    ax_z.axhspan(lo, 0.0, facecolor=FLUTTER_COLOUR, alpha=0.07, lw=0, zorder=0)
    ax_z.axhline(0.0, color="0.3", lw=0.8)
    for ax in (ax_z, ax_f):
        ax.axvline(row.V_D, color=REQUIREMENT_COLOUR, lw=1.0, ls=":")
        ax.axvline(row.V_required, color=REQUIREMENT_COLOUR, lw=1.4, ls="--")
        ax.grid(True, alpha=0.3)
    ax_z.annotate(f"V_D {row.V_D:.1f} m/s", (row.V_D, 1.0), xycoords=("data", "axes fraction"),
                  xytext=(-3, -3), textcoords="offset points", ha="right", va="top", fontsize=8)
    ax_z.annotate(f"required {row.V_required:.1f} m/s", (row.V_required, 1.0),
                  xycoords=("data", "axes fraction"), xytext=(3, -3),
                  textcoords="offset points", ha="left", va="top", fontsize=8)
    if min_damping_g is not None:
        ax_z.plot([V[0], row.V_D], [0.5 * min_damping_g] * 2, "-", color=REQUIREMENT_COLOUR,
                  lw=1.4, label=f"required g ≥ {min_damping_g:g} (ζ ≥ {0.5 * min_damping_g:g})")
    for Ve, fe, kind, event, _mode in p.events:
        colour = FLUTTER_COLOUR if kind == "flutter" else DIVERGENCE_COLOUR
        face = "none" if event == "recovery" else colour
        for ax, y in ((ax_z, 0.0), (ax_f, fe)):
            ax.plot([Ve], [y], "o", ms=7, mec=colour, mfc=face, mew=1.6, zorder=5)
    if row.critical_speed is not None:
        ax_z.annotate(f"V_crit {row.critical_speed:.1f} m/s", (row.critical_speed, 0.0),
                      xytext=(0, -14), textcoords="offset points", ha="center", va="top",
                      fontsize=8, color=FLUTTER_COLOUR if row.kind == "flutter"
                      else DIVERGENCE_COLOUR)
    ax_z.set_ylim(lo, hi)
    ax_z.set_ylabel("damping ratio ζ [-]")
    g_axis = ax_z.secondary_yaxis("right", functions=(lambda z: 2.0 * z, lambda g: 0.5 * g))
    g_axis.set_ylabel("g = 2ζ [-]")
    ax_f.set_ylabel("frequency f [Hz]")
    ax_f.set_xlabel("true airspeed V [m/s]")
    ax_f.set_ylim(bottom=0.0)
    ax_f.set_xlim(float(V[0]), float(V[-1]))
    fig.legend(loc="outside right upper", fontsize=8)
    ax_z.set_title(title or _wrap(f"{row.case} at {row.altitude_m:g} m: V-g-f"), fontsize=10)
    return finish(fig, path)


def hermite(V: np.ndarray, y: np.ndarray, dy: np.ndarray, valid: np.ndarray,
            n: int = HERMITE_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """The cubic Hermite curve through (V, y) with slopes dy [per m/s], `n` points per step
    where both ends are `valid` (the engine's model of a step,
    :func:`propwhirl.engine.hermite.hermite_coeffs`); NaN between (a gap in the drawn line).  A step whose cubic
    leaves the band of its end values widened by their difference and a quarter of the
    curve's whole range is drawn straight: there the slope is near-singular (a branch point) and the cubic would
    invent a peak."""
    xs, ys = [], []
    t = np.linspace(0.0, 1.0, n)
    scale = float(np.ptp(y[valid])) if valid.any() else 0.0
    for j in range(len(V) - 1):
        if not (valid[j] and valid[j + 1]):
            xs.append([np.nan])
            ys.append([np.nan])
            continue
        dV = V[j + 1] - V[j]
        seg = hermite_eval(hermite_coeffs(y[j], y[j + 1], dy[j], dy[j + 1], dV), t)
        lo, hi = min(y[j], y[j + 1]), max(y[j], y[j + 1])
        room = (hi - lo) + 0.25 * scale
        if not np.isfinite(seg).all() or seg.min() < lo - room or seg.max() > hi + room:
            seg = y[j] + t * (y[j + 1] - y[j])     # near a branch point the slope is singular
        xs.append(V[j] + t * dV)
        ys.append(seg)
    if not xs:
        return V[valid], y[valid]
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


def _wrap(text: str, width: int = 90) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width)) or text


def png_bytes(fig: Any, dpi: int = 80) -> bytes:
    """The figure as PNG bytes (for a data: URI)."""
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return buf.getvalue()
