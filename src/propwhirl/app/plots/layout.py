"""Layout helpers of the figures with many modes: mode families and their colours, label text
that wraps, and labels placed without collision.

* :func:`mode_family` — the family of a mode ("wing bending", "wing torsion", "backward whirl",
  "forward whirl", "in-plane", "other") from its name and, for wing modes, its content (the
  analysis's kinetic-energy shares): the name carries the whirl sense
  (:mod:`propwhirl.analysis.naming`), the content says bending or torsion.
* :func:`family_shades` — one hue per family, graded shades within it (the emphasised modes
  of one family stay told apart, their family seen at a glance).
* :func:`place_labels` — annotations placed greedily, each at the nearest free spot around
  its anchor, measured with the renderer's text extents (no two label boxes overlap, every
  box inside its axes when there is room); a leader line joins a label moved off its anchor.
* :func:`end_labels`, :func:`stack_labels` — end labels of curves (a Campbell diagram)
  stacked in a column at least one text height apart, measured the same way.

The placement works in display coordinates of a laid-out figure: :func:`freeze_layout` draws
the figure once (the constrained layout settles the axes) and then switches the layout engine
off, so that the axes do not move after the labels were placed.
"""
from __future__ import annotations

import textwrap
from collections.abc import Mapping, Sequence

import numpy as np

#: families in the order of the legends, with their hue (a matplotlib sequential colormap)
FAMILY_MAPS = {"wing bending": "Blues", "wing torsion": "Purples", "backward whirl": "Reds",
               "forward whirl": "Greens", "in-plane": "Oranges", "other": "Greys"}
#: the family's own colour (legends, thin lines)
FAMILY_COLOURS = {"wing bending": "tab:blue", "wing torsion": "tab:purple",
                  "backward whirl": "tab:red", "forward whirl": "tab:green",
                  "in-plane": "tab:orange", "other": "0.4"}
#: characters per line of a wrapped label
WRAP = 30


def mode_family(label: str, content: Mapping[str, float] | None = None) -> str:
    """Family of a mode named `label` (a name of :func:`propwhirl.analysis.naming.mode_names`,
    old or new style: "backward 3", "backward whirl, propellers 1–6 (collective)", "wing 2").

    "backward"/"forward" in the name: that whirl family; "in-plane", "lag" or "edgewise":
    "in-plane"; a wing mode (or any other): "wing torsion" where `content` (kinetic-energy
    shares by group, :attr:`ModelAnalysis.content`) has more torsion than bending, "wing
    bending" where it has bending, otherwise "other".

    Examples
    --------
    >>> mode_family("backward whirl, propellers 1–6 (collective)")
    'backward whirl'
    >>> mode_family("wing 2", {"bending": 0.2, "torsion": 0.7})
    'wing torsion'
    """
    low = label.lower()
    for word, fam in (("backward", "backward whirl"), ("forward", "forward whirl"),
                      ("in-plane", "in-plane"), ("edgewise", "in-plane"), ("lag", "in-plane")):
        if word in low:
            return fam
    c = content or {}
    tors, bend = float(c.get("torsion", 0.0)), float(c.get("bending", 0.0))
    if tors > bend:
        return "wing torsion"
    if bend > 0.0 or low.startswith("wing"):
        return "wing bending"
    return "other"


def family_shades(families: Sequence[str]) -> list:
    """A colour per entry: the family's hue, shades from dark to medium within a family in
    the order given (one member: the family's own colour)."""
    from matplotlib import colormaps

    count: dict[str, int] = {}
    for fam in families:
        count[fam] = count.get(fam, 0) + 1
    seen: dict[str, int] = {}
    out = []
    for fam in families:
        i = seen.get(fam, 0)
        seen[fam] = i + 1
        n = count[fam]
        if n == 1:
            out.append(FAMILY_COLOURS.get(fam, "0.4"))
            continue
        cmap = colormaps[FAMILY_MAPS.get(fam, "Greys")]
        out.append(cmap(0.95 - 0.5 * i / (n - 1)))
    return out


def wrap(text: str, width: int = WRAP) -> str:
    """`text` wrapped line by line at `width` characters (long mode names in a label)."""
    return "\n".join(textwrap.fill(line, width, break_long_words=False) or line
                     for line in text.split("\n"))


def freeze_layout(fig) -> None:
    """Draw `fig` once (its layout engine settles the axes), then switch the engine off so
    that labels placed in display coordinates stay where they were put."""
    fig.canvas.draw()
    fig.set_layout_engine("none")


def _overlaps(a, b, pad: float) -> bool:
    return not (a.x1 + pad <= b.x0 or b.x1 + pad <= a.x0
                or a.y1 + pad <= b.y0 or b.y1 + pad <= a.y0)


def _inside(box, frame) -> bool:
    return (box.x0 >= frame.x0 and box.x1 <= frame.x1 and box.y0 >= frame.y0
            and box.y1 <= frame.y1)


def _offsets(step_x: float, step_y: float, nx: int, ny: int,
             prefer: str) -> list[tuple[float, float]]:
    """Candidate offsets [points] around an anchor, nearest first (the `prefer`red side
    first at equal distance)."""
    cand = [(i * step_x, j * step_y) for i in range(-nx, nx + 1)
            for j in range(-ny, ny + 1) if (i, j) != (0, 0)]

    def key(o):
        dx, dy = o
        away = {"below": dy > 0, "above": dy < 0, "right": dx < 0}[prefer]
        return (1.5 if away else 1.0) * float(np.hypot(dx, 1.6 * dy))
    return sorted(cand, key=key)


def place_labels(ax, anchors: Sequence[tuple[float, float]], texts: Sequence[str],
                 colours: Sequence, *, fontsize: float = 7.5, avoid: Sequence = (),
                 prefer: str = "below", gid: str = "label", pad: float = 2.0) -> list:
    """Annotate `ax` at data points `anchors` with `texts`, no two boxes overlapping.

    The labels are placed in the order given (put the important ones first), each at the
    nearest offset of a grid around its anchor (steps of about one label width by half a
    label height, up to the whole axes) where its box, padded by `pad` pixels, overlaps no
    label placed before and no bounding box in `avoid` (display coordinates, e.g. markers),
    and lies inside the axes; a leader line joins it to its anchor.  If no spot is free the
    label takes the spot of least overlap (never seen in the figures of this package).  The
    figure's layout must be frozen (:func:`freeze_layout`).  Returns the annotations, with
    ``gid`` set (a test finds them by it).
    """
    fig = ax.figure
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    placed: list = list(avoid)
    out = []
    pts = fig.dpi / 72.0                        # pixels per point
    for (x, y), text, colour in zip(anchors, texts, colours):
        ann = ax.annotate(text, xy=(x, y), xytext=(0.0, 0.0), textcoords="offset points",
                          fontsize=fontsize, color=colour, ha="center", va="center", gid=gid,
                          annotation_clip=False, zorder=6,
                          bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none",
                                    alpha=0.85),
                          arrowprops=dict(arrowstyle="-", color=colour, lw=0.6,
                                          shrinkA=0.0, shrinkB=3.0))
        box = _text_box(ann, renderer)                  # at offset 0: centred on the anchor
        w, h = box.width / pts, box.height / pts
        nx = int(frame.width / max(0.55 * box.width, 1.0)) + 1
        ny = int(frame.height / max(0.55 * box.height, 1.0)) + 1
        best, best_cost = (0.0, 0.0), np.inf
        for dx, dy in _offsets(0.55 * w, 0.55 * h, nx, ny, prefer):
            b = box.translated(dx * pts, dy * pts)
            if not _inside(b, frame):
                continue
            cost = sum(_overlap_area(b, o, pad) for o in placed)
            if cost < best_cost:
                best, best_cost = (dx, dy), cost
                if cost == 0.0:
                    break
        ann.xyann = best
        placed.append(_text_box(ann, renderer))
        out.append(ann)
    return out


def _overlap_area(a, b, pad: float) -> float:
    w = min(a.x1, b.x1) + pad - max(a.x0, b.x0)
    h = min(a.y1, b.y1) + pad - max(a.y0, b.y0)
    return max(w, 0.0) * max(h, 0.0)


def end_labels(ax, x_end: float, ends: Sequence[float], texts: Sequence[str],
               colours: Sequence, *, dx_points: float = 14.0, fontsize: float = 8.0,
               gid: str = "label") -> list:
    """Labels of curves ending at (`x_end`, `ends`) [data], `dx_points` to the right of the
    ends, with leader lines; made before the layout is settled (so that it makes room for
    them) and stacked after it by :func:`stack_labels`.  Returns the annotations."""
    return [ax.annotate(text, xy=(x_end, y), xycoords="data", xytext=(dx_points, 0.0),
                        textcoords="offset points", fontsize=fontsize, color=colour,
                        va="center", ha="left", gid=gid, annotation_clip=False,
                        arrowprops=dict(arrowstyle="-", color="0.6", lw=0.6, shrinkA=0,
                                        shrinkB=0))
            for y, text, colour in zip(ends, texts, colours)]


def stack_labels(ax, anns: Sequence) -> None:
    """Move the end labels `anns` (:func:`end_labels`) vertically into a column, each as
    near its curve's end as the others allow and at least one text height (measured with
    the renderer) from the next, inside the axes' height when they fit.  The layout must be
    frozen (:func:`freeze_layout`)."""
    from propwhirl.app.plots.canvas import spread_labels

    if not anns:
        return
    fig = ax.figure
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    pts = fig.dpi / 72.0
    ys = [float(ax.transData.transform(a.xy)[1]) for a in anns]
    gap = max(_text_box(a, renderer).height for a in anns) + 1.5
    pos = spread_labels(ys, gap=gap, lo=frame.y0 + 0.5 * gap, hi=frame.y1 - 0.5 * gap)
    for a, y, p in zip(anns, ys, pos):
        a.xyann = (a.xyann[0], (p - y) / pts)


def label_boxes(fig, gid: str = "label") -> list:
    """Display-coordinate boxes of the texts of `fig` with ``gid`` (for checks)."""
    renderer = fig.canvas.get_renderer()
    return [_text_box(t, renderer) for ax in fig.axes for t in ax.texts
            if t.get_gid() == gid]


def _text_box(t, renderer):
    """The box of a Text's (or an Annotation's) text alone, not of its leader line."""
    from matplotlib.text import Text

    if hasattr(t, "update_positions"):          # an Annotation: place its text first
        t.update_positions(renderer)
    return Text.get_window_extent(t, renderer)


def overlapping(boxes: Sequence) -> list[tuple[int, int]]:
    """Pairs (i, j), i < j, of `boxes` that overlap (touching edges do not)."""
    return [(i, j) for i in range(len(boxes)) for j in range(i + 1, len(boxes))
            if _overlaps(boxes[i], boxes[j], -1e-6)]
