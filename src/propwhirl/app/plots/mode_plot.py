"""Mode shapes: the complex mode shape of a model at one eigenvalue, as a grid that scales to
many propellers.

Top panel (full width): the wing's plunge h and twist α along the span (h on the left axis, α
on the right), Re x̂ (the shape at ωt = 0) and the envelope ±|x̂| that
x(t) = Re(x̂) cos ωt − Im(x̂) sin ωt sweeps over a cycle (eq. 5.11–5.12 without the decay), the
propeller positions marked P1, P2, ….  Below, one small θ–ψ orbit panel per propeller in a
grid of up to four columns, titled "propeller 3 (y = 3.0 m)" with the whirl sense relative to
that propeller's own rotation (:func:`propwhirl.analysis.whirl.whirl_sense`) and its amplitude
√(|θ̂|² + |ψ̂|²) relative to the largest propeller's.  All orbit panels share one scale, so the
sizes compare directly.  Propellers are numbered from 1.
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from propwhirl import validate as v
from propwhirl.analysis.whirl import whirl_sense
from propwhirl.app.plots.canvas import finish, new_figure

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from propwhirl.analysis.stability import Instability, ModelAnalysis
    from propwhirl.model.protocol import DofMap

#: columns of the propeller-orbit grid
ORBIT_COLUMNS = 4
H_COLOUR, ALPHA_COLOUR, ORBIT_COLOUR = "C0", "C3", "C2"


def normalised(eigenvector, dof_map: "DofMap") -> np.ndarray:
    """The displacement part of `eigenvector` (full-state or displacements) scaled so that its
    largest h, α, θ or ψ entry is 1 and real (θ and ψ also of a modal structure's hub grids,
    :meth:`~propwhirl.model.protocol.DofMap.whirling`)."""
    x = np.asarray(eigenvector, dtype=complex).ravel()
    dm = dof_map
    if x.size not in (dm.n_dof, dm.n_states):
        raise v.InputError(f"eigenvector has {x.size} entries: need {dm.n_dof} (displacements) "
                           f"or {dm.n_states} (states) for this model")
    shown = [i for i, k in enumerate(dm.q_kinds) if k in ("h", "alpha", "theta", "psi")]
    if not shown and not dm.hubs:
        raise v.InputError("the model has no wing node (h, alpha) or propeller (theta, psi) "
                           "states: nothing to plot")
    x = x[: dm.n_dof]
    vals = np.concatenate([x[shown], *(p.pitch_yaw(x) for p in dm.whirling()
                                       if p.dofs is None)])
    ref = vals[int(np.argmax(np.abs(vals)))]
    if abs(ref) == 0:
        raise v.InputError("the eigenvector is zero in every plotted state")
    return x / ref


def wing_values(x: np.ndarray, dof_map: "DofMap", key: str) -> np.ndarray:
    """Complex `key` ("h" or "alpha") at every wing node (the clamped root 0 as zero):
    :meth:`~propwhirl.model.protocol.DofMap.wing_values`."""
    return dof_map.wing_values(x, key)


def propeller_amplitudes(x: np.ndarray, dof_map: "DofMap") -> dict[int, float]:
    """{propeller number: √(|θ̂|² + |ψ̂|²) / the largest of them}."""
    amp = {p.number: float(np.hypot(*np.abs(p.pitch_yaw(x)))) for p in dof_map.whirling()}
    top = max(amp.values(), default=0.0)
    return {j: (a / top if top > 0 else 0.0) for j, a in amp.items()}


def propeller_title(p, x: np.ndarray, lam: complex, amplitude: float | None = None,
                    share: float | None = None) -> str:
    """'propeller 3 (y = 3 m): 61 %' and, on a second line, the whirl sense and amplitude;
    ``share``: the propeller's share of the mode's kinetic energy
    (:mod:`propwhirl.analysis.participation`), shown when given."""
    where = f" (y = {p.y:.3g} m)" if p.y is not None else ""
    part = "" if share is None else f": {100 * share:.0f} %"
    sense = (f"{whirl_sense(*p.pitch_yaw(x), p.rotation, lam)} whirl"
             if complex(lam).imag != 0 else "planar (real root)")
    amp = "" if amplitude is None else f", amplitude {amplitude:.2f}"
    return f"propeller {p.number + 1}{where}{part}\n{sense}{amp}"


def orbit(x: np.ndarray, p, lam: complex, n: int = 181) -> tuple[np.ndarray, np.ndarray]:
    """θ(t), ψ(t) over one cycle, ωt from 0 to 2π (eq. 5.11 without the decay); ``p`` a
    :class:`~propwhirl.model.protocol.PropellerMotion`."""
    phase = np.linspace(0.0, 2.0 * np.pi, n)
    rot = np.exp(1j * (1.0 if complex(lam).imag >= 0 else -1.0) * phase)
    th, ps = p.pitch_yaw(x)
    return (th * rot).real, (ps * rot).real


def mode_shape(eigenvector, eigenvalue: complex, dof_map: "DofMap", *,
               title: str | None = None, path: str | Path | None = None,
               shares: "dict[int, float] | None" = None) -> "Figure":
    """Plot a complex mode shape (full-state or displacement eigenvector) of a model.

    ``dof_map`` (``model.dof_map()``, or ``ModelAnalysis.dof_map``) says which entries are
    which wing node's h and α and which propeller's θ and ψ.  Layout in the module docstring:
    the wing panel (h and α [per unit of the largest entry] against the node positions y [m])
    above a grid of θ–ψ orbit panels, one per propeller.  The vector is normalised by
    :func:`normalised`.  ``shares``: {propeller number from 1: its share of the mode's kinetic
    energy}, written in the orbit panels' titles (:func:`event_mode_shape` passes the event's).

    Parameters
    ----------
    eigenvector : array_like
        Full-state or displacement eigenvector (complex).
    eigenvalue : complex
        Its eigenvalue λ [1/s] (the orbits' whirl sense, the title's frequency).
    dof_map : DofMap
        What each state is.
    title : str, optional
        Figure title.
    path : str or Path, optional
        File to write.
    shares : dict of int to float, optional
        {propeller number from 1: its share [-] of the mode's kinetic energy}.

    Returns
    -------
    matplotlib.figure.Figure
        The wing panels (h and α against y [m]; none without a wing) and one θ–ψ orbit
        panel per flexibly mounted propeller.

    Examples
    --------
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> model = isolated_baseline_propeller()
    >>> a = analyse(model, speeds=[100.0, 200.0, 250.0])
    >>> from propwhirl.app.plots import event_eigenvector, mode_shape
    >>> x, lam, V = event_eigenvector(a, a.critical)
    >>> fig = mode_shape(x, lam, a.dof_map)
    >>> fig.axes[-1].get_title().splitlines()[0]
    'propeller 1'
    """
    dm = dof_map
    x = normalised(eigenvector, dm)
    lam = complex(eigenvalue)
    has_wing = any(n >= 0 for n in dm.q_node) and len(dm.node_y) > 0
    props = dm.whirling()
    ncol = min(ORBIT_COLUMNS, max(len(props), 1))
    nrow = -(-len(props) // ncol) if props else 0
    rows = ([2.2] if has_wing else []) + [2.0] * nrow
    fig = new_figure(figsize=(max(3.1 * ncol, 8.0 if has_wing else 3.4), 0.8 + 1.55 * sum(rows)),
                     layout="constrained")
    grid = fig.add_gridspec(len(rows), ncol, height_ratios=rows)
    if has_wing:
        _wing_panel(fig.add_subplot(grid[0, :]), x, dm, props)
    amps = propeller_amplitudes(x, dm)
    r0 = 1 if has_wing else 0
    orbits = {p.number: orbit(x, p, lam) for p in props}
    extent = max((float(np.max(np.abs(np.r_[t, s]))) for t, s in orbits.values()), default=1.0)
    extent = 1.1 * (extent or 1.0)
    first = None
    for i, p in enumerate(props):
        ax = fig.add_subplot(grid[r0 + i // ncol, i % ncol], sharex=first, sharey=first)
        first = first or ax
        t_path, p_path = orbits[p.number]
        ax.plot(t_path, p_path, "-", color=ORBIT_COLOUR, lw=1.6)
        ax.plot([t_path[0]], [p_path[0]], "o", color=ORBIT_COLOUR, ms=5)
        k = 12
        ax.annotate("", xy=(t_path[k + 3], p_path[k + 3]), xytext=(t_path[k], p_path[k]),
                    arrowprops=dict(arrowstyle="->", color=ORBIT_COLOUR, lw=1.6))
        ax.set_title(propeller_title(p, x, lam, amps[p.number] if len(props) > 1 else None,
                                     None if shares is None else shares.get(p.number + 1)),
                     fontsize=9)
        ax.axhline(0.0, color="0.3", lw=0.8)
        ax.axvline(0.0, color="0.3", lw=0.8)
        ax.set_xlim(-extent, extent)
        ax.set_ylim(-extent, extent)
        ax.set_aspect("equal", adjustable="box")
        ax.grid(True, alpha=0.3)
        ax.tick_params(labelsize=8)
        if i % ncol == 0:
            ax.set_ylabel("ψ (yaw)", fontsize=9)
        if i // ncol == nrow - 1 or i + ncol >= len(props):
            ax.set_xlabel("θ (pitch)", fontsize=9)
    f_hz = abs(lam.imag) / (2 * np.pi)
    zeta = -lam.real / abs(lam) if lam != 0 else 0.0
    fig.suptitle(title or f"mode shape: λ = {lam.real:.4g} {'+' if lam.imag >= 0 else '−'} "
                 f"{abs(lam.imag):.4g}i 1/s (f = {f_hz:.3f} Hz, ζ = {zeta:.3g})", fontsize=11)
    return finish(fig, path)


def _wing_panel(ax, x: np.ndarray, dm: "DofMap", props) -> None:
    y = np.asarray(dm.node_y, dtype=float)
    ax_a = ax.twinx()
    for axis, key, name, colour in ((ax, "h", "plunge h (down)", H_COLOUR),
                                    (ax_a, "alpha", "twist α (nose up)", ALPHA_COLOUR)):
        vals = wing_values(x, dm, key)
        env = np.abs(vals)
        axis.fill_between(y, -env, env, color=colour, alpha=0.12, lw=0)
        axis.plot(y, vals.real, "-", color=colour, lw=1.7, label=f"{name}: Re x̂ (ωt = 0)")
        axis.plot(y, env, ":", color=colour, lw=1.0, label=f"{name}: envelope ±|x̂|")
        axis.set_ylabel(f"{name} [normalised]", color=colour)
        axis.tick_params(axis="y", colors=colour)
        top = float(env.max()) or 1.0
        axis.set_ylim(-1.15 * top, 1.15 * top)    # zero at mid-height on both axes
    for p in props:
        if p.y is not None:
            ax.axvline(p.y, color="0.5", lw=0.8, ls="--")
            ax.annotate(f"P{p.number + 1}", (p.y, 1.0), xycoords=("data", "axes fraction"),
                        xytext=(0, 2), textcoords="offset points", ha="center", va="bottom",
                        fontsize=8, color="0.3")
    ax.axhline(0.0, color="0.3", lw=0.8)
    ax.set_xlim(0.0, y[-1] * 1.01)
    ax.set_xlabel("spanwise position y [m]")
    ax.set_title("wing", fontsize=10, loc="left")
    ax.grid(True, alpha=0.3)
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax_a.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=7.5, loc="lower left", ncol=2)


def event_eigenvector(analysis: "ModelAnalysis", event: "Instability") -> tuple[np.ndarray, complex, float]:
    """(full-state eigenvector, eigenvalue, V [m/s]) of an instability event.

    The refined critical point's vector where the analysis has it (onsets and recoveries of
    a fresh analysis); otherwise the tracked mode's vector at the sweep speed nearest the
    event (frequency-zero events, or analyses re-read with eigenvectors).

    Parameters
    ----------
    analysis : ModelAnalysis
        The analysis.
    event : Instability
        One of its events.

    Returns
    -------
    eigenvector : ndarray
        Full-state eigenvector (complex).
    eigenvalue : complex
        λ [1/s].
    V : float
        The speed of the vector [m/s].

    Examples
    --------
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> model = isolated_baseline_propeller()
    >>> a = analyse(model, speeds=[100.0, 200.0, 250.0])
    >>> from propwhirl.app.plots import event_eigenvector
    >>> x, lam, V = event_eigenvector(a, a.critical)
    >>> import math
    >>> x.shape, round(V, 1), round(abs(lam.imag) / (2 * math.pi), 2)       # V [m/s], f [Hz]
    ((4,), 221.5, 5.01)
    """
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


def event_title(analysis: "ModelAnalysis", event: "Instability", lam: complex, V: float) -> str:
    """'model: flutter (onset) of forward 1' and, on a second line, 'V = 170.04 m/s,
    f = 6.763 Hz, backward whirl'."""
    whirl = f", {event.whirl} whirl" if event.whirl else ""
    return (f"{analysis.model_name}: {event.kind} ({event.event}) of {event.label}\n"
            f"V = {V:.2f} m/s, f = {abs(lam.imag) / (2 * np.pi):.3f} Hz{whirl}")


def check_event(analysis: "ModelAnalysis", event: "Instability | None") -> None:
    """InputError unless `event` is an instability whose mode shape `analysis` can give (it
    has a DOF map)."""
    if event is None:
        raise v.InputError("no instability to plot (event is None)")
    if analysis.dof_map is None:
        raise v.InputError("this analysis has no DOF map (saved by an older propwhirl): "
                           "re-run the analysis to plot its mode shapes")


def event_mode_shape(analysis: "ModelAnalysis", event: "Instability", *,
                     path: str | Path | None = None) -> "Figure":
    """:func:`mode_shape` of an instability of `analysis` (e.g. ``analysis.critical``).

    Parameters
    ----------
    analysis : ModelAnalysis
        The analysis (fresh, or re-read with its eigenvectors).
    event : Instability
        One of its events.
    path : str or Path, optional
        File to write.

    Returns
    -------
    matplotlib.figure.Figure
        As :func:`mode_shape`, titled with the event, its speed [m/s] and frequency [Hz].

    Examples
    --------
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> model = isolated_baseline_propeller()
    >>> a = analyse(model, speeds=[100.0, 200.0, 250.0])
    >>> from propwhirl.app.plots import event_mode_shape
    >>> fig = event_mode_shape(a, a.critical)
    >>> fig.get_suptitle().splitlines()[-1].startswith("V = 221.50 m/s")
    True
    """
    check_event(analysis, event)
    x, lam, V = event_eigenvector(analysis, event)
    part = getattr(event, "participation", None)
    shares = None if part is None else {q.propeller: q.share for q in part.propellers}
    return mode_shape(x, lam, analysis.dof_map, title=event_title(analysis, event, lam, V),
                      path=path, shares=shares)
