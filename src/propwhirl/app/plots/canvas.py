"""Figures of :mod:`propwhirl.app.plots`: creation, saving, display in notebooks, colours.

Matplotlib is optional (the ``plots`` extra) and imported only when a figure is made; without
it every plot function raises :class:`~propwhirl.validate.InputError` saying how to install it.
Figures are built with matplotlib's object-oriented API on an Agg canvas (no pyplot, no global
backend switch), so they work headless and in threads.

Display in Jupyter: a figure made without pyplot is unknown to IPython's inline backend (that
backend registers its PNG formatter only when pyplot is imported), so a cell ending in
``plots.vgf(r)`` used to show ``<Figure size 1000x700 with 2 Axes>``.  Every figure here is a
:class:`PlotFigure`, a matplotlib Figure with ``_repr_png_``: IPython's display formatter
renders it inline, with or without ``%matplotlib inline`` (where the inline backend is active
its formatter for Figure is used instead: one image either way).
"""
from __future__ import annotations

import functools
import io
from pathlib import Path
from typing import TYPE_CHECKING

from propwhirl import fileio
from propwhirl import validate as v

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

#: Marker colours of Figure 7.4
FLUTTER_COLOUR = "red"
DIVERGENCE_COLOUR = "green"
INSTALL_HINT = "install the plots extra: pip install propwhirl[plots]"
#: resolution of the notebook image [dots per inch]
NOTEBOOK_DPI = 100


def matplotlib_or_error() -> None:
    """Import matplotlib or raise the InputError naming the ``plots`` extra."""
    try:
        import matplotlib  # noqa: F401
    except ImportError as exc:
        raise v.InputError(f"plotting needs matplotlib, which is not installed: {INSTALL_HINT}") from exc


@functools.cache
def _figure_class() -> type:
    """:class:`PlotFigure`, defined on first use (matplotlib imported lazily)."""
    from matplotlib.figure import Figure

    class PlotFigure(Figure):
        """A matplotlib Figure that IPython displays inline (``_repr_png_``)."""

        def _repr_png_(self) -> bytes:
            buf = io.BytesIO()
            self.savefig(buf, format="png", dpi=NOTEBOOK_DPI)
            return buf.getvalue()

    PlotFigure.__module__ = __name__
    PlotFigure.__qualname__ = "PlotFigure"
    return PlotFigure


def new_figure(**kwargs) -> "Figure":
    """A new :class:`PlotFigure` on an Agg canvas (`kwargs` go to matplotlib's Figure)."""
    matplotlib_or_error()
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = _figure_class()(**kwargs)
    FigureCanvasAgg(fig)
    return fig


def save(fig: "Figure", path: str | Path, dpi: int = 150) -> Path:
    """Write `fig` to `path` (format from the suffix, e.g. .png; PNG without one); returns
    the path.  The file is replaced atomically (:func:`propwhirl.fileio.write_with`).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : str or Path
        The file; its suffix is the format (.png, .pdf, .svg, ...).
    dpi : int
        Dots per inch.

    Returns
    -------
    Path
        `path`.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> import numpy as np
    >>> from propwhirl.app.plots import campbell_diagram, save
    >>> fig = campbell_diagram(np.array([0.0, 1000.0]), np.array([[5.0], [5.5]]))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     png = save(fig, pathlib.Path(folder) / "campbell.png", dpi=30)
    ...     head = png.read_bytes()[1:4]              # the PNG signature
    >>> png.name, head
    ('campbell.png', b'PNG')
    """
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


def finish(fig: "Figure", path: str | Path | None) -> "Figure":
    """`fig`, written to `path` first if given."""
    if path is not None:
        save(fig, path)
    return fig


def colours(n: int) -> list:
    """`n` distinct colours (tab10, tab20 beyond ten)."""
    from matplotlib import colormaps

    cmap = colormaps["tab10" if n <= 10 else "tab20"]
    return [cmap(i % cmap.N) for i in range(n)]


def spread_labels(y: list[float], gap: float, lo: float, hi: float) -> list[float]:
    """Label positions near `y` (data units), at least `gap` apart, inside [lo, hi], order
    kept: the labels of curves ending close together do not overlap.

    The positions p closest to `y` in least squares with p_(k+1) − p_k ≥ gap (sorted by y):
    with q_k = p_k − k·gap the constraint is q non-decreasing, and pooling adjacent
    violators (each pool of labels centred on the mean of its curves' ends) gives q in one
    pass.  (Re-centring clusters in turns, as before, could oscillate between two
    groupings and stop with labels overlapping: six propellers' Campbell diagram.)

    Examples
    --------
    >>> spread_labels([1.0, 1.1, 5.0], gap=0.5, lo=0.0, hi=10.0)
    [0.8, 1.3, 5.0]
    """
    if not y:
        return []
    n = len(y)
    order = sorted(range(n), key=lambda i: y[i])
    pools: list[list[float]] = []                     # [mean of q, count] of each pool
    for k, i in enumerate(order):
        pools.append([float(y[i]) - k * gap, 1.0])
        while len(pools) > 1 and pools[-2][0] > pools[-1][0]:
            m2, c2 = pools.pop()
            m1, c1 = pools.pop()
            pools.append([(m1 * c1 + m2 * c2) / (c1 + c2), c1 + c2])
    q = [m for m, c in pools for _ in range(int(c))]
    pos = [q[k] + k * gap for k in range(n)]
    shift = max(0.0, lo - pos[0]) - max(0.0, pos[-1] - hi)
    pos = [round(p + shift, 12) for p in pos]
    out = [0.0] * n
    for k, i in enumerate(order):
        out[i] = pos[k]
    return out
