"""Time histories: θ(t), ψ(t) and the θ–ψ path of one propeller (Figures 9.11–9.12)."""
from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from propwhirl import validate as v
from propwhirl.app.plots.canvas import finish, new_figure
from propwhirl.engine import TimeResponse

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure


def time_history(responses: TimeResponse | Mapping[str, TimeResponse], *,
                 propeller: int = 0, title: str | None = None,
                 path: str | Path | None = None) -> "Figure":
    """θ(t), ψ(t) [deg] and the θ–ψ path of one propeller (Figures 9.11–9.12).

    `responses`: one TimeResponse or {legend label: TimeResponse} (e.g. one per airspeed);
    the states 'propeller k theta' / 'propeller k psi' of ``propeller`` = k − 1 (the index in
    the model, from 0; labels and the figure number propellers from 1: index 0 is
    "propeller 1").

    Parameters
    ----------
    responses : TimeResponse or mapping of str to TimeResponse
        The time histories (t [s]; θ, ψ [rad], drawn in degrees), with legend labels.
    propeller : int
        Index of the propeller in the model, from 0.
    title : str, optional
        Figure title.
    path : str or Path, optional
        File to write.

    Returns
    -------
    matplotlib.figure.Figure
        Three axes: θ(t), ψ(t) [deg] against t [s], and the θ–ψ path.

    Examples
    --------
    The isolated baseline propeller released from θ = 0.01 rad below and above its flutter
    speed (221.5 m/s):

    >>> from propwhirl.analysis.response import simulate
    >>> from propwhirl.app.plots import time_history
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> model = isolated_baseline_propeller()
    >>> runs = {f"{V:g} m/s": simulate(model, V, {"propeller 1 theta": 0.01}, duration=2.0,
    ...                                dt=0.01) for V in (200.0, 240.0)}
    >>> fig = time_history(runs)
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['θ (pitch) [deg]', 'ψ (yaw) [deg]', 'ψ (yaw) [deg]']
    >>> [line.get_label() for line in fig.axes[0].get_lines()]
    ['200 m/s', '240 m/s']
    """
    if isinstance(responses, TimeResponse):
        responses = {"": responses}
    if not responses:
        raise v.InputError("responses is empty: give at least one TimeResponse")
    names = (f"propeller {propeller + 1} theta", f"propeller {propeller + 1} psi")
    fig = new_figure(figsize=(12.0, 4.5), layout="constrained")
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
    fig.suptitle(title or f"propeller {propeller + 1}: time response")
    return finish(fig, path)
