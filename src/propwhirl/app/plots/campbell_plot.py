"""Campbell diagram: natural frequencies against propeller rotational speed.

The curves are the tracked modes of :func:`propwhirl.analysis.vibration.campbell` (each mode
followed along the speed, not the frequencies sorted at each speed), coloured by family
(wing bending, wing torsion, backward whirl, forward whirl), each named at its right end with
the names spread so that they do not overlap.  The excitation lines 1P (f = n/60, n the
propeller speed [rev/min]) and 2P (f = 2n/60) are drawn for each distinct propeller speed:
where the propellers turn at different speeds (``rpm_ratio``), one pair of lines per speed,
labelled with the propellers (numbered from 1) that turn at it.
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from propwhirl import validate as v
from propwhirl.analysis.vibration import campbell as campbell_data
from propwhirl.app.plots.canvas import finish, new_figure
from propwhirl.analysis.naming import mode_family
from propwhirl.app.plots.layout import (FAMILY_COLOURS, end_labels, freeze_layout, stack_labels,
                                        wrap)

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

    from propwhirl.analysis.vibration import CampbellResult

#: line styles of the excitation orders 1P, 2P
ORDER_STYLES = {1: "--", 2: ":"}


def campbell(model, rpm=None, *, rpm_ratio=None, n_modes: int | None = None,
             title: str | None = None, path: str | Path | None = None) -> "Figure":
    """Campbell diagram of a PropellerWing or an IsolatedPropeller
    (:func:`propwhirl.analysis.vibration.campbell`, aerodynamics off) drawn by
    :func:`campbell_diagram`; `rpm` [rev/min] and `rpm_ratio` as there.

    Parameters
    ----------
    model : PropellerWing or IsolatedPropeller
        With at least one flexibly mounted propeller.
    rpm : array_like, optional
        Rotational speeds [rev/min] of the first propeller that turns, ≥ 0, increasing
        (default 0–6000 every 250).
    rpm_ratio : sequence of float, optional
        Each propeller's speed relative to the first turning one's (default: as they
        operate).
    n_modes : int, optional
        Draw the lowest n modes (default :func:`default_count`).
    title : str, optional
        Figure title (default: the model's name).
    path : str or Path, optional
        File to write (PNG, or the format of the suffix).

    Returns
    -------
    matplotlib.figure.Figure
        One axes: natural frequency f [Hz] against propeller speed n [rpm], the 1P and 2P
        lines.

    Examples
    --------
    The isolated baseline propeller's backward and forward whirl modes split with rpm:

    >>> import numpy as np
    >>> from propwhirl.app.plots import campbell
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> fig = campbell(isolated_baseline_propeller(), rpm=np.linspace(0.0, 3000.0, 7))
    >>> ax = fig.axes[0]
    >>> ax.get_xlabel(), ax.get_ylabel()
    ('propeller rotational speed n [rpm]', 'natural frequency f [Hz]')
    """
    c = campbell_data(model, rpm, rpm_ratio=rpm_ratio)
    return campbell_diagram(c, n_modes=n_modes, title=title or f"{model.name}: Campbell diagram",
                            path=path)


def default_count(families: Sequence[str], frequencies: np.ndarray) -> int:
    """How many of the lowest modes to draw: every whirl mode and the wing modes whose
    frequency at the lowest speed is below 1.2 × the highest whirl frequency (at least 4)."""
    f = np.asarray(frequencies, dtype=float)
    whirl = [i for i, fam in enumerate(families) if "whirl" in fam]
    if not whirl:
        return min(8, f.shape[1])
    top = 1.2 * float(np.nanmax(f[:, whirl]))
    keep = [i for i in range(f.shape[1]) if i in whirl or f[0, i] <= top]
    return max(min(4, f.shape[1]), max(keep) + 1)


def campbell_diagram(rpm, frequencies=None, *, n_modes: int | None = None,
                     names: Sequence[str] | None = None, families: Sequence[str] | None = None,
                     rpm_ratio: Sequence[float] | None = None, title: str | None = None,
                     path: str | Path | None = None) -> "Figure":
    """Plot a Campbell diagram.

    Parameters
    ----------
    rpm : CampbellResult or array_like
        A :class:`~propwhirl.analysis.vibration.CampbellResult` (its names, families and
        propeller speed ratios are used), or the speeds [rev/min] of the first propeller.
    frequencies : array_like, optional
        (len(rpm), n) [Hz] when `rpm` is an array: column i one tracked mode, lowest first.
    n_modes : int, optional
        Draw the first n columns (default :func:`default_count`).
    names, families, rpm_ratio
        With arrays: mode names (label each curve), families (colour; default from the
        names by :func:`propwhirl.analysis.naming.mode_family`), each propeller's speed
        relative to the first's.
    title, path
        Figure title; file to write.

    Returns
    -------
    matplotlib.figure.Figure
        One axes: f [Hz] against n [rpm], a line per mode, the 1P and 2P lines.

    Examples
    --------
    Two modes given as arrays, on an Agg canvas:

    >>> import numpy as np
    >>> from propwhirl.app.plots import campbell_diagram
    >>> rpm = np.array([0.0, 1000.0, 2000.0])
    >>> f = np.array([[5.0, 7.0], [4.5, 7.5], [4.0, 8.0]])          # [Hz]
    >>> fig = campbell_diagram(rpm, f, names=["backward 1", "forward 1"])
    >>> [line.get_label() for line in fig.axes[0].get_lines()][-2:]
    ['1P (f = n/60)', '2P (f = 2n/60)']
    """
    if frequencies is None and hasattr(rpm, "frequency_hz"):
        c: CampbellResult = rpm
        rpm, frequencies = c.rpm, c.frequency_hz
        names, families = c.labels, c.families or None
        rpm_ratio = c.rpm_ratio or None
    r = np.asarray(rpm, dtype=float)
    f = np.asarray(frequencies, dtype=float)
    if f.ndim != 2 or f.shape[0] != r.size:
        raise v.InputError(f"frequencies must have shape (len(rpm), n) = ({r.size}, n), got {f.shape}")
    names = list(names) if names is not None else [f"mode {i + 1}" for i in range(f.shape[1])]
    families = list(families) if families is not None else [mode_family(nm) for nm in names]
    n = (default_count(families, f) if n_modes is None
         else min(v.integer_at_least("n_modes", n_modes, 1), f.shape[1]))
    n = min(n, f.shape[1])
    fig = new_figure(figsize=(9.0, 6.0), layout="constrained")
    ax = fig.subplots()
    for i in range(n):
        ax.plot(r, f[:, i], "-", color=FAMILY_COLOURS.get(families[i], "0.4"), lw=1.6,
                marker="." if r.size < 30 else None)
    top = 1.12 * float(np.nanmax(f[:, :n])) if n else 1.0
    _excitation_lines(ax, r, rpm_ratio, top)
    ax.set_ylim(0.0, top)
    span = float(r[-1] - r[0]) if r.size > 1 else max(float(r[0]), 1.0)
    x_end = float(r[-1])
    ax.set_xlim(float(r[0]), x_end + 0.16 * span)
    anns = []
    if r.size:
        ends = [float(f[-1, i]) for i in range(n)]
        anns = end_labels(ax, x_end, ends, [wrap(nm) for nm in names[:n]],
                          [FAMILY_COLOURS.get(fam, "0.2") for fam in families[:n]],
                          dx_points=12.0, gid=LABEL_GID)
    _rpm_axes(ax, rpm_ratio)
    ax.set_ylabel("natural frequency f [Hz]")
    ax.grid(True, alpha=0.3)
    from matplotlib.lines import Line2D

    handles, labels = ax.get_legend_handles_labels()
    present = [fam for fam in FAMILY_COLOURS if fam in families[:n]]
    handles = [Line2D([], [], color=FAMILY_COLOURS[fam], lw=2) for fam in present] + handles
    labels = present + labels
    ax.legend(handles, labels, loc="upper left", fontsize=8.5)
    fig.suptitle(title or "Campbell diagram")
    ax.set_title(AERO_NOTE, fontsize=8.5, color="0.3")
    freeze_layout(fig)
    stack_labels(ax, anns)
    return finish(fig, path)


#: the note under every Campbell diagram
AERO_NOTE = ("aerodynamics off: natural frequencies of the undamped gyroscopic system "
             "(no airspeed, no aerodynamic stiffness or damping)")
#: ``gid`` of the curves' end labels
LABEL_GID = "label"


def _groups(rpm_ratio) -> list[tuple[float, list[int]]]:
    """(ratio, propellers numbered from 1) per distinct propeller speed, fastest first."""
    ratios = [1.0] if not rpm_ratio else [float(x) for x in rpm_ratio]
    groups: dict[float, list[int]] = {}
    for j, q in enumerate(ratios):
        groups.setdefault(q, []).append(j + 1)
    return sorted(groups.items(), reverse=True)


def _who(props: Sequence[int]) -> str:
    """'propeller 7', 'propellers 1–6', 'propellers 1, 3, 5'."""
    if len(props) == 1:
        return f"propeller {props[0]}"
    run = list(range(props[0], props[-1] + 1)) == list(props)
    return f"propellers {props[0]}–{props[-1]}" if run and len(props) > 2 else \
        "propellers " + ", ".join(map(str, props))


def _rpm_axes(ax, rpm_ratio) -> None:
    """x label in the first propeller's rpm; where the propellers turn at different speeds
    the bottom axis names the propellers at the first's speed and one axis on top per other
    speed gives theirs [rev/min]."""
    groups = _groups(rpm_ratio)
    if len(groups) == 1:
        ax.set_xlabel("propeller rotational speed n [rpm]")
        return
    ratios = [1.0] if not rpm_ratio else [float(x) for x in rpm_ratio]
    base = ratios[0]
    first = next(props for q, props in groups if q == base)
    ax.set_xlabel(f"rotational speed n of {_who(first)} [rpm]")
    others = [(q, props) for q, props in groups if q != base]
    for i, (q, props) in enumerate(others[:3]):
        k = q / base
        sec = ax.secondary_xaxis("top" if i == 0 else 1.0 + 0.12 * i,
                                 functions=(lambda x, k=k: k * x, lambda x, k=k: x / k))
        sec.set_xlabel(f"rotational speed of {_who(props)} [rpm]", fontsize=9)


def _excitation_lines(ax, r: np.ndarray, rpm_ratio, top: float) -> None:
    """1P and 2P lines, one pair per distinct propeller speed (labelled with its propellers)."""
    groups = _groups(rpm_ratio)
    shades = ["0.35", "tab:brown", "tab:olive", "tab:cyan", "tab:pink", "tab:gray"]
    for g, (q, props) in enumerate(groups):
        who = _who(props)
        for order, style in ORDER_STYLES.items():
            k = "" if order == 1 else str(order)
            label = (f"{order}P (f = {k}n/60)" if len(groups) == 1
                     else f"{order}P of {who} (at {q:.3g} n)")
            ax.plot(r, order * q * r / 60.0, style, color=shades[g % len(shades)], lw=1.0,
                    label=label)
