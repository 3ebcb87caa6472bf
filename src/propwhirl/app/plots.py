"""Plots: V-g-f diagrams, Campbell diagrams, mode shapes at critical points, time histories.

Matplotlib is optional (the ``plots`` extra) and imported only when a plot is drawn; without it
every function raises :class:`~propwhirl.validate.InputError` saying how to install it.  The
figures are built with matplotlib's object-oriented API on an Agg canvas (no pyplot, no global
backend switch), so they work headless and in threads.  Every function returns the
:class:`matplotlib.figure.Figure` and, given ``path``, also writes it (PNG by the suffix).

* :func:`vgf` — damping ratio ζ (eq. 5.5) and frequency [Hz] against airspeed of a
  :class:`~propwhirl.analysis.stability.ModelAnalysis`, one line per tracked physical mode with its name,
  instabilities marked as in Figure 7.4 (flutter red, divergence green; filled at an onset,
  open at a recovery);
* :func:`campbell` — tracked frequencies against propeller RPM (:func:`propwhirl.analysis.vibration.campbell`);
* :func:`mode_shape` / :func:`event_mode_shape` — the complex mode shape at a critical point:
  wing h and α along the span (real and imaginary parts and the envelope |x̂| of
  x(t) = Re(x̂) cos ωt − Im(x̂) sin ωt, eq. 5.11–5.12) and each propeller's θ–ψ orbit;
* :func:`time_history` — θ(t), ψ(t) and the θ–ψ path of
  :class:`~propwhirl.engine.TimeResponse` results (Figures 9.11–9.12).
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Mapping, Sequence

import numpy as np

from propwhirl.analysis.whirl import whirl_sense
from propwhirl.engine import TimeResponse
from propwhirl import fileio
from propwhirl import validate as v

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from propwhirl.analysis.stability import Instability, ModelAnalysis
    from propwhirl.model.protocol import DofMap

#: Marker colours of Figure 7.4
FLUTTER_COLOUR = "red"
DIVERGENCE_COLOUR = "green"
INSTALL_HINT = "install the plots extra: pip install propwhirl[plots]"


def _figure(**kwargs) -> "Figure":
    """A new Figure on an Agg canvas (matplotlib imported here, lazily)."""
    try:
        import matplotlib  # noqa: F401  (explicit: fails cleanly when matplotlib is absent)
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as exc:
        raise v.InputError(f"plotting needs matplotlib, which is not installed: {INSTALL_HINT}") from exc
    fig = Figure(**kwargs)
    FigureCanvasAgg(fig)
    return fig


def save(fig: "Figure", path: str | Path, dpi: int = 150) -> Path:
    """Write `fig` to `path` (format from the suffix, e.g. .png; PNG without one); returns
    the path.  The file is replaced atomically (:func:`propwhirl.fileio.write_with`)."""
    path = Path(path)
    fmt = path.suffix[1:].lower() or "png"
    supported = fig.canvas.get_supported_filetypes()
    if fmt not in supported:
        raise v.InputError(f"cannot write plot {str(path)!r}: format {fmt!r} is not supported "
                           f"(suffixes: {', '.join(sorted(supported))})")
    try:
        return fileio.write_with(path, lambda fh: fig.savefig(fh, format=fmt, dpi=dpi),
                                 what="plot")
    except ValueError as exc:  # matplotlib's (InputError from fileio passes as it is)
        if isinstance(exc, v.InputError):
            raise
        raise v.InputError(f"cannot write plot {str(path)!r}: {exc}") from exc


def _finish(fig: "Figure", path: str | Path | None) -> "Figure":
    if path is not None:
        save(fig, path)
    return fig


# ----------------------------------------------------------------------------- V-g-f
def select_modes(analysis: "ModelAnalysis", n_modes: int | None = None,
                 labels: Sequence[str] | None = None, include_lag: bool = False) -> list[int]:
    """Mode ids to plot: physical modes at the first speed, the aerodynamic lag roots only if
    asked, optionally only the named `labels`, then the lowest `n_modes` by frequency at the
    first speed."""
    sw = analysis.sweep
    phys0 = sw.physical[0]
    ids = [k for k in range(sw.n_modes) if phys0[k]
           and (include_lag or not sw.mode_labels[k].startswith("lag"))]
    if labels is not None:
        unknown = [lab for lab in labels if lab not in sw.mode_labels]
        if unknown:
            raise v.InputError(f"mode labels {unknown} not in the analysis: modes are "
                               f"{', '.join(sw.mode_labels[k] for k in ids)}")
        ids = [k for k in ids if sw.mode_labels[k] in labels]
    ids.sort(key=lambda k: (sw.frequency_hz[0, k], k))
    if n_modes is not None:
        ids = ids[: v.integer_at_least("n_modes", n_modes, 1)]
    return ids


def vgf(analysis: "ModelAnalysis", *, n_modes: int | None = None,
        labels: Sequence[str] | None = None, include_lag: bool = False,
        title: str | None = None, path: str | Path | None = None) -> "Figure":
    """V-g-f diagram: ζ and f [Hz] against V [m/s], one line per tracked physical mode.

    `n_modes`: only the lowest n modes by frequency at the first speed; `labels`: only these
    modes; `include_lag`: also the real aerodynamic lag roots (off: they clutter).  Where a
    complex pair splits into two real roots the second root (the partner branch) is drawn
    dashed in the mode's colour.  Instabilities of the drawn modes are marked: flutter red,
    divergence green (Figure 7.4); filled at onsets, open at recoveries.
    """
    sw = analysis.sweep
    ids = select_modes(analysis, n_modes, labels, include_lag)
    if not ids:
        raise v.InputError("no modes to plot: the selection is empty")
    fig = _figure(figsize=(10.0, 7.0), layout="constrained")
    ax_z, ax_f = fig.subplots(2, 1, sharex=True)
    cmap = _colours(len(ids))
    V = sw.V
    zeta, freq, phys = sw.damping_ratio, sw.frequency_hz, sw.physical
    drawn = set()
    for i, k in enumerate(ids):
        colour = cmap[i]
        for branch, style, name in ((k, "-", sw.mode_labels[k]), (int(sw.partner[k]), "--", None)):
            if branch < 0 or not phys[:, branch].any():
                continue
            mask = phys[:, branch]
            ax_z.plot(*_broken(V, np.where(mask, zeta[:, branch], np.nan)), style, color=colour,
                      lw=1.4, label=name)
            ax_f.plot(V, np.where(mask, freq[:, branch], np.nan), style, color=colour, lw=1.4)
            drawn.add(branch)
    for e in analysis.events:
        if e.mode not in drawn:
            continue
        colour = FLUTTER_COLOUR if e.kind == "flutter" else DIVERGENCE_COLOUR
        face = colour if e.event != "recovery" else "none"
        for ax, y in ((ax_z, 0.0), (ax_f, e.frequency_hz)):
            ax.plot([e.V], [y], "o", ms=8, mec=colour, mfc=face, mew=1.8, zorder=5)
    ax_z.axhline(0.0, color="0.3", lw=0.8)
    ax_z.set_ylabel("damping ratio ζ")
    ax_z.set_ylim(*_zeta_limits(zeta[:, sorted(drawn)], phys[:, sorted(drawn)]))
    ax_f.set_ylabel("frequency [Hz]")
    ax_f.set_xlabel("airspeed V [m/s]")
    ax_f.set_ylim(bottom=0.0)
    ax_f.set_xlim(V[0], V[-1])
    for ax in (ax_z, ax_f):
        ax.grid(True, alpha=0.3)
    handles, names = ax_z.get_legend_handles_labels()
    from matplotlib.lines import Line2D

    handles += [Line2D([], [], ls="", marker="o", mec=FLUTTER_COLOUR, mfc=FLUTTER_COLOUR, ms=8),
                Line2D([], [], ls="", marker="o", mec=DIVERGENCE_COLOUR, mfc=DIVERGENCE_COLOUR, ms=8)]
    names += ["flutter", "divergence"]
    fig.legend(handles, names, loc="outside right upper", fontsize=9)
    fig.suptitle(title or f"{analysis.model_name}: V-g-f")
    return _finish(fig, path)


def _broken(V: np.ndarray, y: np.ndarray, jump: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """(V, y) with NaN inserted where y jumps by more than `jump` between samples — a real
    root crossing zero turns ζ from +1 to −1 at once (eq. 5.5): no sloped line is drawn."""
    cut = np.nonzero(np.abs(np.diff(y)) > jump)[0] + 1
    return np.insert(V.astype(float), cut, np.nan), np.insert(y.astype(float), cut, np.nan)


def _zeta_limits(zeta: np.ndarray, phys: np.ndarray) -> tuple[float, float]:
    """ζ axis: the oscillatory range with a margin; real roots (ζ = ±1) are clipped unless
    they are all there is."""
    z = zeta[phys & (np.abs(zeta) < 0.999)]
    if z.size == 0:
        return -1.05, 1.05
    lo, hi = min(float(z.min()), 0.0), max(float(z.max()), 0.0)
    pad = 0.08 * max(hi - lo, 1e-3)
    return lo - pad, hi + pad


def _colours(n: int) -> list:
    from matplotlib import colormaps

    cmap = colormaps["tab10" if n <= 10 else "tab20"]
    return [cmap(i % cmap.N) for i in range(n)]


# ----------------------------------------------------------------------------- Campbell
def campbell(model, rpm, *, n_modes: int | None = 8, title: str | None = None,
             path: str | Path | None = None) -> "Figure":
    """Campbell diagram of a PropellerWing: natural frequencies [Hz] against RPM, each mode
    followed along the speeds (:func:`propwhirl.analysis.vibration.campbell`, aerodynamics off):
    the `n_modes` lowest at RPM 0, named there (in-vacuo names), and the 1P line (f = RPM/60)."""
    from propwhirl.analysis.vibration import campbell as campbell_data

    c = campbell_data(model, rpm)
    return campbell_diagram(c.rpm, c.frequency_hz, n_modes=n_modes, names=c.labels,
                            title=title or f"{model.name}: Campbell diagram",
                            path=path)


def campbell_diagram(rpm, frequencies, *, n_modes: int | None = 8,
                     names: Sequence[str] | None = None, title: str | None = None,
                     path: str | Path | None = None) -> "Figure":
    """Plot frequencies (len(rpm), n) [Hz] against rpm [rev/min]: column i is one curve (a
    tracked mode of :class:`propwhirl.analysis.vibration.CampbellResult`, lowest first), named
    ``names[i]`` at the lowest rpm; the first `n_modes` columns are drawn."""
    rpm = np.asarray(rpm, dtype=float)
    f = np.asarray(frequencies, dtype=float)
    if f.ndim != 2 or f.shape[0] != rpm.size:
        raise v.InputError(f"frequencies must have shape (len(rpm), n) = ({rpm.size}, n), got {f.shape}")
    n = f.shape[1] if n_modes is None else min(v.integer_at_least("n_modes", n_modes, 1), f.shape[1])
    fig = _figure(figsize=(8.0, 6.0), layout="constrained")
    ax = fig.subplots()
    for i in range(n):
        ax.plot(rpm, f[:, i], "-", color="C0", lw=1.4, marker="." if rpm.size < 30 else None)
    if names is not None and rpm.size:
        i0 = int(np.argmin(rpm))
        for i, name in enumerate(list(names)[:n]):
            ax.annotate(name, (rpm[i0], f[i0, i]), xytext=(4, 3), textcoords="offset points",
                        fontsize=8)
    ax.plot(rpm, rpm / 60.0, "--", color="0.4", lw=1.0, label="1P (f = RPM/60)")
    top = float(np.nanmax(f[:, :n])) if n else 1.0
    ax.set_ylim(0.0, 1.1 * top)
    ax.set_xlabel("propeller rotational speed [RPM]")
    ax.set_ylabel("frequency [Hz]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", fontsize=9)
    fig.suptitle(title or "Campbell diagram")
    return _finish(fig, path)


# ----------------------------------------------------------------------------- mode shapes
def mode_shape(eigenvector, eigenvalue: complex, dof_map: "DofMap", *,
               title: str | None = None, path: str | Path | None = None) -> "Figure":
    """Plot a complex mode shape (full-state or displacement eigenvector) of a model.

    ``dof_map`` (``model.dof_map()``, or ``ModelAnalysis.dof_map``) says which entries are
    which wing node's h and α and which propeller's θ and ψ.  Wing panels: h and α at the nodes
    (the clamped root, node 0, is added as zero) against the node positions y [m].  Shown are
    Re(x̂) (the shape at ωt = 0), Im(x̂) (dashed: x(t) at ωt = −π/2 by eq. 5.12) and the
    envelope ±|x̂| (shaded) that x(t) = Re(x̂) cos ωt − Im(x̂) sin ωt sweeps over a cycle
    (eq. 5.11 without the decay).  Propeller panels: the θ–ψ orbit over one cycle, the start
    (ωt = 0) dotted, an arrow in the direction of motion, titled with the whirl sense relative
    to that propeller's own sense of rotation (:func:`propwhirl.analysis.whirl.whirl_sense`).
    The vector is normalised so that its largest displacement entry is 1 and real (entries in
    m and rad per unit of that entry).
    """
    x = np.asarray(eigenvector, dtype=complex).ravel()
    dm = dof_map
    if x.size not in (dm.n_dof, dm.n_states):
        raise v.InputError(f"eigenvector has {x.size} entries: need {dm.n_dof} (displacements) "
                           f"or {dm.n_states} (states) for this model")
    props = {p.number: p for p in dm.propellers}
    nodes = sorted({n for n in dm.q_node if n >= 0})
    shown = [i for i, k in enumerate(dm.q_kinds) if k in ("h", "alpha", "theta", "psi")]
    if not shown:
        raise v.InputError("the model has no wing node (h, alpha) or propeller (theta, psi) "
                           "states: nothing to plot")
    ref = shown[int(np.argmax(np.abs(x[shown])))]
    if abs(x[ref]) == 0:
        raise v.InputError("the eigenvector is zero in every plotted state")
    x = x / x[ref]
    lam = complex(eigenvalue)
    n_panels = (2 if nodes else 0) + len(props)
    fig = _figure(figsize=(4.2 * n_panels + 1.0, 4.2), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, n_panels))
    col = 0
    if nodes:
        y = np.asarray(dm.node_y, dtype=float)
        for key, name, unit in (("h", "h (positive down)", "m"), ("alpha", "α (nose up)", "rad")):
            vals = np.zeros(y.size, dtype=complex)
            for node in range(y.size):
                i = dm.wing_dof(node, key)
                if i is not None:
                    vals[node] = x[i]
            ax = axes[col]
            env = np.abs(vals)
            ax.fill_between(y, -env, env, color="C0", alpha=0.15, lw=0, label="envelope ±|x̂|")
            ax.plot(y, vals.real, "-", color="C0", lw=1.6, label="Re x̂  (ωt = 0)")
            ax.plot(y, vals.imag, "--", color="C3", lw=1.4, label="Im x̂  (ωt = −π/2)")
            ax.axhline(0.0, color="0.3", lw=0.8)
            ax.set_xlabel("spanwise position y [m]")
            ax.set_ylabel(f"{name} [{unit}, normalised]")
            ax.set_title(f"wing {name.split(' ')[0]}")
            ax.grid(True, alpha=0.3)
            col += 1
        axes[0].legend(fontsize=8, loc="best")
    phase = np.linspace(0.0, 2.0 * np.pi, 181)
    w_sign = 1.0 if lam.imag >= 0 else -1.0
    for j in sorted(props):
        p = props[j]
        th, ps = x[p.theta], x[p.psi]
        rot = np.exp(1j * w_sign * phase)
        t_path, p_path = (th * rot).real, (ps * rot).real
        ax = axes[col]
        ax.plot(t_path, p_path, "-", color="C2", lw=1.6)
        ax.plot([t_path[0]], [p_path[0]], "o", color="C2", ms=6)
        k = 12
        ax.annotate("", xy=(t_path[k + 3], p_path[k + 3]), xytext=(t_path[k], p_path[k]),
                    arrowprops=dict(arrowstyle="->", color="C2", lw=1.6))
        sense = whirl_sense(th, ps, p.rotation, lam) if lam.imag != 0 else "planar (real root)"
        where = f" (y = {p.y:.3g} m)" if p.y is not None else ""
        ax.set_title(f"propeller {j}{where}: {sense} whirl" if "real" not in sense
                     else f"propeller {j}{where}: {sense}")
        ax.set_xlabel("θ (pitch) [rad, normalised]")
        ax.set_ylabel("ψ (yaw) [rad, normalised]")
        ax.axhline(0.0, color="0.3", lw=0.8)
        ax.axvline(0.0, color="0.3", lw=0.8)
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(True, alpha=0.3)
        col += 1
    f_hz = abs(lam.imag) / (2 * np.pi)
    zeta = -lam.real / abs(lam) if lam != 0 else 0.0
    fig.suptitle(title or f"mode shape: λ = {lam.real:.4g} {'+' if lam.imag >= 0 else '−'} "
                 f"{abs(lam.imag):.4g}i 1/s (f = {f_hz:.3f} Hz, ζ = {zeta:.3g})")
    return _finish(fig, path)


def event_eigenvector(analysis: "ModelAnalysis", event: "Instability") -> tuple[np.ndarray, complex, float]:
    """(full-state eigenvector, eigenvalue, V [m/s]) of an instability event.

    The refined critical point's vector where the analysis has it (onsets and recoveries of
    a fresh analysis); otherwise the tracked mode's vector at the sweep speed nearest the
    event (frequency-zero events, or analyses re-read with eigenvectors)."""
    crit = analysis.criticals
    if crit is not None:
        for p in crit.points:
            if p.mode == event.mode and abs(p.V - event.V) <= 1e-9 * max(1.0, abs(event.V)):
                return np.asarray(p.eigenvector), complex(p.eigenvalue), float(p.V)
    sw = analysis.sweep
    if sw.eigenvectors is None:
        raise v.InputError(f"no eigenvector for the {event.kind} of {event.label} at "
                           f"{event.V:.2f} m/s: the analysis was saved without eigenvectors")
    t = int(np.argmin(np.abs(sw.V - event.V)))
    return sw.eigenvectors[t, :, event.mode], complex(sw.eigenvalues[t, event.mode]), float(sw.V[t])


def event_mode_shape(analysis: "ModelAnalysis", event: "Instability", *,
                     path: str | Path | None = None) -> "Figure":
    """:func:`mode_shape` of an instability of `analysis` (e.g. ``analysis.critical``)."""
    if event is None:
        raise v.InputError("no instability to plot (event is None)")
    if analysis.dof_map is None:
        raise v.InputError("this analysis has no DOF map (saved by an older propwhirl): "
                           "re-run the analysis to plot its mode shapes")
    x, lam, V = event_eigenvector(analysis, event)
    whirl = f", {event.whirl} whirl" if event.whirl else ""
    title = (f"{analysis.model_name}: {event.kind} ({event.event}) of {event.label} at "
             f"V = {V:.2f} m/s, f = {abs(lam.imag) / (2 * np.pi):.3f} Hz{whirl}")
    return mode_shape(x, lam, analysis.dof_map, title=title, path=path)


# ----------------------------------------------------------------------------- time histories
def time_history(responses: TimeResponse | Mapping[str, TimeResponse], *,
                 propeller: int = 0, title: str | None = None,
                 path: str | Path | None = None) -> "Figure":
    """θ(t), ψ(t) [deg] and the θ–ψ path of one propeller (Figures 9.11–9.12).

    `responses`: one TimeResponse or {legend label: TimeResponse} (e.g. one per airspeed);
    the states 'propeller j theta' / 'propeller j psi' are plotted."""
    if isinstance(responses, TimeResponse):
        responses = {"": responses}
    if not responses:
        raise v.InputError("responses is empty: give at least one TimeResponse")
    names = (f"propeller {propeller} theta", f"propeller {propeller} psi")
    fig = _figure(figsize=(12.0, 4.5), layout="constrained")
    ax_t, ax_p, ax_o = fig.subplots(1, 3)
    for i, (label, r) in enumerate(responses.items()):
        th, ps = (np.degrees(r[n]) for n in names)  # r[...] names the missing state on error
        c = f"C{i % 10}"
        ax_t.plot(r.t, th, color=c, lw=1.2, label=label or None)
        ax_p.plot(r.t, ps, color=c, lw=1.2)
        ax_o.plot(th, ps, color=c, lw=1.0)
        ax_o.plot([th[0]], [ps[0]], "o", color=c, ms=5)
    for ax, ylabel in ((ax_t, "θ (pitch) [deg]"), (ax_p, "ψ (yaw) [deg]")):
        ax.set_xlabel("t [s]")
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
    ax_o.set_xlabel("θ (pitch) [deg]")
    ax_o.set_ylabel("ψ (yaw) [deg]")
    ax_o.set_aspect("equal", adjustable="datalim")
    ax_o.grid(True, alpha=0.3)
    if any(responses):
        ax_t.legend(fontsize=8)
    fig.suptitle(title or f"propeller {propeller}: time response")
    return _finish(fig, path)
