"""Spanwise sensitivities of a critical speed: where along the span stiffness or mass helps.

:func:`spanwise_sensitivity` draws, for the per-element parameters of
:func:`propwhirl.analysis.sensitivity.critical_sensitivities` (EI, GJ and the mass per length of
each element), the normalised sensitivity (p / V_crit) dV_crit/dp [-] at each element's
midpoint y [m], one panel per property, with the propeller stations marked.  Summed over the
elements a panel gives the sensitivity to the whole distribution (printed in its title).
"""
from __future__ import annotations

import re
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from propwhirl import validate as v
from propwhirl.app.plots.canvas import finish, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: the per-element properties drawn, with their labels
PROPERTIES = (("EI", "bending rigidity EI"), ("GJ", "torsional rigidity GJ"),
              ("mass_per_length", "mass per length m"))
_ELEMENT = re.compile(r"^wing\.(\w+)\[(\d+)\]$")


def spanwise_sensitivity(cs, model, *, path: str | Path | None = None) -> "Figure":
    """The normalised sensitivities of ``cs`` (a CriticalSensitivities of ``model``) to the
    per-element EI, GJ and mass along the span (module docstring).  Written to `path` if given.

    Parameters
    ----------
    cs : CriticalSensitivities
        Sensitivities with per-element parameters (``wing.EI[i]``, ``wing.GJ[i]``,
        ``wing.mass_per_length[i]``).
    model : PropellerWing
        The model they are of.
    path : str or Path, optional
        File to write.

    Returns
    -------
    matplotlib.figure.Figure
        A panel per property given: the normalised sensitivity [-] at each element's
        midpoint y [m].

    Examples
    --------
    The baseline wing on 4 elements with the tip propeller: its divergence (143 m/s) is
    raised by torsional rigidity near the root.

    >>> from propwhirl.analysis import analyse, critical_sensitivities
    >>> from propwhirl.app.plots import spanwise_sensitivity
    >>> from propwhirl.model import Installation, PropellerWing
    >>> from propwhirl.cases.ch09_baseline import baseline_flight, baseline_propeller, baseline_wing
    >>> m = PropellerWing(baseline_wing(n_elements=4), baseline_flight(),
    ...                   (Installation(baseline_propeller(), 5.7),))
    >>> a = analyse(m, speeds=[50.0, 100.0, 150.0, 200.0])
    >>> cs = critical_sensitivities(m, a, params=[f"wing.GJ[{i}]" for i in range(4)])
    >>> [round(s.normalised, 2) for s in cs.sensitivities]
    [0.25, 0.16, 0.06, 0.01]
    >>> fig = spanwise_sensitivity(cs, m)
    >>> len(fig.axes), fig.axes[-1].get_xlabel()
    (1, 'spanwise position y [m] (element midpoints)')
    """
    ys = np.asarray(model.wing.node_y, dtype=float)
    mid = 0.5 * (ys[:-1] + ys[1:])
    values: dict[str, np.ndarray] = {name: np.full(mid.size, np.nan) for name, _ in PROPERTIES}
    for s in cs.sensitivities:
        m = _ELEMENT.match(s.path)
        if m and m.group(1) in values:
            values[m.group(1)][int(m.group(2))] = s.normalised
    shown = [(n, lab) for n, lab in PROPERTIES if np.isfinite(values[n]).any()]
    if not shown:
        raise v.InputError("no per-element sensitivities to draw (compute them for the wing's "
                           "elements: params=None)")
    fig = new_figure(figsize=(8.5, 2.4 * len(shown) + 0.9), layout="constrained")
    axes = fig.subplots(len(shown), 1, sharex=True, squeeze=False)[:, 0]
    stations = [float(ys[n]) for n in getattr(model, "nodes", ())]
    for ax, (name, label) in zip(axes, shown):
        s = values[name]
        ax.bar(mid, s, width=0.9 * np.diff(ys), color=np.where(s >= 0, "tab:blue", "tab:red"))
        ax.axhline(0.0, color="0.3", lw=0.8)
        for j, y in enumerate(stations):
            ax.axvline(y, color="0.5", ls="--", lw=0.8)
            ax.annotate(f"P{j + 1}", (y, 1.0), xycoords=("data", "axes fraction"),
                        ha="center", va="bottom", fontsize=8, color="0.4")
        ax.set_ylabel("(p/V) dV/dp [-]")
        ax.set_title(f"{label}: sum over the elements {np.nansum(s):+.4f}", fontsize=10,
                     loc="left")
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel("spanwise position y [m] (element midpoints)")
    fig.suptitle(f"{model.name}: sensitivity of the {cs.kind} {cs.event} of {cs.mode} "
                 f"({cs.V:.2f} m/s)\nnormalised (p/V) dV/dp per element; > 0: raising p raises "
                 "the critical speed", fontsize=10)
    return finish(fig, path)
