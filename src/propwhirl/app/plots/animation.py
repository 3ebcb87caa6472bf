"""Animation of a mode shape over one cycle, written as a GIF.

The motion is x(t) = Re(x̂ e^{iωt}) = Re(x̂) cos ωt − Im(x̂) sin ωt (eq. 5.11–5.12, the decay
left out so that the loop repeats): the wing's plunge h and twist α along the span, and each
propeller's θ–ψ point running round its orbit (the layout of
:func:`propwhirl.app.plots.mode_shape`, propellers numbered from 1).  Frames are drawn with
matplotlib on an Agg canvas and joined into a looping GIF with Pillow (a dependency of
matplotlib), written atomically (:func:`propwhirl.fileio.write_with`).
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from propwhirl import fileio
from propwhirl import validate as v
from propwhirl.app.plots.mode_plot import (ALPHA_COLOUR, H_COLOUR, ORBIT_COLOUR, check_event,
                                           event_eigenvector, event_title, mode_shape,
                                           normalised, orbit, wing_values)

if TYPE_CHECKING:  # pragma: no cover
    from propwhirl.analysis.stability import Instability, ModelAnalysis
    from propwhirl.model.protocol import DofMap

#: default number of frames per cycle, frames per second and resolution [dots per inch]
FRAMES, FPS, DPI = 36, 12, 72


def animate_mode(eigenvector, eigenvalue: complex, dof_map: "DofMap", path: str | Path, *,
                 frames: int = FRAMES, fps: float = FPS, dpi: float = DPI,
                 title: str | None = None) -> Path:
    """Write a GIF of the mode (`frames` per cycle at `fps` frames per second, `dpi` dots per
    inch); returns the path.  Arguments as :func:`~propwhirl.app.plots.mode_shape`, which draws the still
    figure the frames are made from (the orbits stay as the path, a dot moves on each).

    Parameters
    ----------
    eigenvector : array_like
        Full-state or displacement eigenvector (complex).
    eigenvalue : complex
        Its eigenvalue λ [1/s].
    dof_map : DofMap
        What each state is.
    path : str or Path
        The GIF to write.
    frames : int
        Frames per cycle.
    fps : float
        Frames per second [1/s].
    dpi : float
        Dots per inch.
    title : str, optional
        Figure title.

    Returns
    -------
    Path
        `path`.

    Examples
    --------
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> model = isolated_baseline_propeller()
    >>> a = analyse(model, speeds=[100.0, 200.0, 250.0])
    >>> import pathlib, tempfile
    >>> from propwhirl.app.plots import animate_mode, event_eigenvector
    >>> x, lam, V = event_eigenvector(a, a.critical)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     gif = animate_mode(x, lam, a.dof_map, pathlib.Path(folder) / "mode.gif",
    ...                        frames=2, dpi=30)
    ...     head = gif.read_bytes()[:6]
    >>> head
    b'GIF89a'
    """
    n = v.integer_at_least("frames", frames, 2)
    v.in_range("fps", fps, 0.5, 60.0, "frames/s")
    path = Path(path)
    if path.suffix.lower() != ".gif":
        raise v.InputError(f"animation path {str(path)!r} is invalid: must end in .gif")
    dm = dof_map
    x = normalised(eigenvector, dm)
    lam = complex(eigenvalue)
    v.in_range("dpi", dpi, 20.0, 300.0, "dots per inch")
    fig = mode_shape(x, lam, dm, title=title)
    fig.set_dpi(dpi)
    sign = 1.0 if lam.imag >= 0 else -1.0
    phases = 2.0 * np.pi * np.arange(n) / n
    movers = []                                      # (artist, update(phase))
    props = dm.whirling()
    axes = fig.axes
    wing = [ax for ax in axes if ax.get_title(loc="left") == "wing"]
    if wing:
        ax_h = wing[0]
        ax_a = next(ax for ax in axes if ax is not ax_h and ax.bbox.bounds == ax_h.bbox.bounds)
        y = np.asarray(dm.node_y, dtype=float)
        for ax, key, colour in ((ax_h, "h", H_COLOUR), (ax_a, "alpha", ALPHA_COLOUR)):
            vals = wing_values(x, dm, key)
            (line,) = ax.plot(y, vals.real, "-", color=colour, lw=3.0, alpha=0.9)
            movers.append((line, lambda ph, line=line, vals=vals:
                           line.set_ydata((vals * np.exp(1j * sign * ph)).real)))
    orbit_axes = [ax for ax in axes if ax.get_title().startswith("propeller")]
    for ax, p in zip(orbit_axes, props):
        th, ps = p.pitch_yaw(x)
        (dot,) = ax.plot([th.real], [ps.real], "o", color="k", ms=7, zorder=6)
        (spoke,) = ax.plot([0.0, th.real], [0.0, ps.real], "-", color="k", lw=1.0)

        def move(ph, dot=dot, spoke=spoke, th=th, ps=ps):
            rot = np.exp(1j * sign * ph)
            t, s = (th * rot).real, (ps * rot).real
            dot.set_data([t], [s])
            spoke.set_data([0.0, t], [0.0, s])
        movers.append((dot, move))
    from PIL import Image

    images = []
    for ph in phases:
        for _, update in movers:
            update(ph)
        fig.canvas.draw()
        rgba = np.asarray(fig.canvas.buffer_rgba())
        images.append(Image.fromarray(rgba[..., :3].copy()).convert(
            "P", palette=Image.Palette.ADAPTIVE, colors=128))
    duration = int(round(1000.0 / fps))

    def fill(fh):
        images[0].save(fh, format="GIF", save_all=True, append_images=images[1:],
                       duration=duration, loop=0, optimize=False)

    return fileio.write_with(path, fill, what="animation")


def animate_event(analysis: "ModelAnalysis", event: "Instability", path: str | Path, *,
                  frames: int = FRAMES, fps: float = FPS, dpi: float = DPI) -> Path:
    """:func:`animate_mode` of an instability of `analysis` (e.g. ``analysis.critical``).

    Parameters
    ----------
    analysis : ModelAnalysis
        The analysis (fresh, or re-read with its eigenvectors).
    event : Instability
        One of its events.
    path : str or Path
        The GIF to write.
    frames : int
        Frames per cycle.
    fps : float
        Frames per second [1/s].
    dpi : float
        Dots per inch.

    Returns
    -------
    Path
        `path`.

    Examples
    --------
    >>> from propwhirl.analysis import analyse
    >>> from propwhirl.cases.ch09_baseline import isolated_baseline_propeller
    >>> model = isolated_baseline_propeller()
    >>> a = analyse(model, speeds=[100.0, 200.0, 250.0])
    >>> import pathlib, tempfile
    >>> from propwhirl.app.plots import animate_event
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     gif = animate_event(a, a.critical, pathlib.Path(folder) / "critical.gif",
    ...                         frames=2, dpi=30)
    ...     size = gif.stat().st_size
    >>> gif.name, size > 0
    ('critical.gif', True)
    """
    check_event(analysis, event)
    x, lam, V = event_eigenvector(analysis, event)
    return animate_mode(x, lam, analysis.dof_map, path, frames=frames, fps=fps, dpi=dpi,
                        title=event_title(analysis, event, lam, V))
